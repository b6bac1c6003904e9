// One-contact nonsmooth functions of the Newton family (AC, JM, NM, FB):
// zeros exactly at Coulomb's law (stick, slide, take-off), Jacobian elements
// against central finite differences at random non-degenerate points of
// every branch, and valid generalised-Jacobian elements at the kinks
// (take-off / stick / slide boundaries): the returned element matches a
// one-sided directional derivative, i.e. the derivative of an adjacent piece.
#include <fcsolve/cone/cones.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/formulation/alart_curnier.hpp>
#include <fcsolve/formulation/fischer_burmeister.hpp>
#include <fcsolve/formulation/jean_moreau.hpp>
#include <fcsolve/formulation/natural_map.hpp>

#include <catch2/catch.hpp>

#include <random>

using namespace fcsolve;

static_assert(is_one_contact_function_v<AlartCurnierFunction<Coulomb3D>> &&
              is_one_contact_function_v<JeanMoreauFunction<Coulomb2D>> &&
              is_one_contact_function_v<NaturalMapFunction<Frictionless>> &&
              is_one_contact_function_v<FischerBurmeisterFunction<Coulomb3D>>);

namespace {

template <class F, class Cone>
struct Case {
  using Vec = typename Cone::Vec;
  using Mat = SmallMatrix<Cone::dim>;
  static constexpr int D = Cone::dim;

  /// Central differences of G in (u, r): columns of A and B.
  static void finite_differences(const Vec& r, const Vec& u, double mu, const Vec& rho, double h,
                                 Mat& A, Mat& B) {
    for (int j = 0; j < D; ++j) {
      Vec e = Vec::Zero();
      e[j] = h;
      A.col(j) = (F::value(r, u + e, mu, rho) - F::value(r, u - e, mu, rho)) / (2 * h);
      B.col(j) = (F::value(r + e, u, mu, rho) - F::value(r - e, u, mu, rho)) / (2 * h);
    }
  }

  /// The element (A, B) at a kink matches the one-sided directional
  /// derivative G'(p; d) = A du + B dr for at least one of many directions.
  static int matching_directions(const Vec& r, const Vec& u, double mu, const Vec& rho,
                                 std::mt19937& gen) {
    Vec G;
    Mat A, B;
    F::value_and_jacobian(r, u, mu, rho, G, A, B);
    std::normal_distribution<double> normal;
    int matches = 0;
    const double t = 1e-7;
    for (int k = 0; k < 200; ++k) {
      Vec dr, du;
      for (int i = 0; i < D; ++i) {
        dr[i] = normal(gen);
        du[i] = normal(gen);
      }
      // At u_T = 0, g(u) = (mu ||u_T||, 0) has the one-sided derivative
      // mu ||du_T||, linear in no open set of directions: the element there
      // (the zero subgradient of the norm) is checked along du_T = 0.
      if (D >= 2 && u.tail(D - 1).norm() == 0) du.tail(D - 1).setZero();
      const Vec slope = (F::value(r + t * dr, u + t * du, mu, rho) - G) / t;
      if ((slope - (A * du + B * dr)).norm() <= 1e-5 * (1 + dr.norm() + du.norm())) ++matches;
    }
    return matches;
  }
};

template <class F, class Cone>
void check_random_points(std::uint32_t seed, int* branch_count = nullptr) {
  using C = Case<F, Cone>;
  using Vec = typename C::Vec;
  using Mat = typename C::Mat;
  std::mt19937 gen(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0, 1);
  for (int k = 0; k < 2000; ++k) {
    Vec r, u, rho;
    for (int i = 0; i < C::D; ++i) {
      r[i] = normal(gen);
      u[i] = normal(gen);
      rho[i] = 0.3 + 3 * uniform(gen);
    }
    const double mu = k % 10 == 0 ? 0.0 : 0.05 + 1.5 * uniform(gen);
    Vec G;
    Mat A, B, Afd, Bfd;
    F::value_and_jacobian(r, u, mu, rho, G, A, B);
    C::finite_differences(r, u, mu, rho, 1e-6, Afd, Bfd);
    INFO("point " << k << " mu " << mu << "\nr " << r.transpose() << "\nu " << u.transpose()
                  << "\nrho " << rho.transpose() << "\nA\n" << A << "\nA fd\n" << Afd << "\nB\n"
                  << B << "\nB fd\n" << Bfd);
    REQUIRE((G - F::value(r, u, mu, rho)).norm() == 0.0);
    REQUIRE((A - Afd).cwiseAbs().maxCoeff() <= 1e-5 * (1 + A.cwiseAbs().maxCoeff()));
    REQUIRE((B - Bfd).cwiseAbs().maxCoeff() <= 1e-5 * (1 + B.cwiseAbs().maxCoeff()));
    if (branch_count && C::D >= 2) {  // Alart-Curnier regions, to prove coverage
      const double xn = r[0] - rho[0] * u[0];
      const double R = mu * std::max(xn, 0.0);
      const double xt = (r.tail(C::D - 1) - rho.tail(C::D - 1).cwiseProduct(u.tail(C::D - 1))).norm();
      ++branch_count[xn <= 0 ? 0 : (xt <= R ? 1 : 2)];
    }
  }
}

/// Points satisfying Coulomb's law at one contact, and one that does not.
template <class F, class Cone>
void check_zeros() {
  using Vec = typename Cone::Vec;
  constexpr int D = Cone::dim;
  const double mu = 0.6;
  Vec rho = Vec::Constant(1.7);
  rho[0] = 0.8;
  Vec t = Vec::Zero();  // unit tangent
  if (D >= 2) t[1] = 0.6;
  if (D == 3) t[2] = -0.8;
  if (D == 2) t[1] = 1;
  // take-off: r = 0, u_N > 0, any u_T
  Vec r = Vec::Zero(), u = 2 * t;
  u[0] = 0.5;
  CHECK(F::value(r, u, mu, rho).norm() <= 1e-15);
  // stick: r in int K, u = 0
  r = 0.3 * mu * t;
  r[0] = 1;
  u.setZero();
  CHECK(F::value(r, u, mu, rho).norm() <= 1e-15);
  if (D >= 2) {
    // slide: u_N = 0, u_T = s t, r = r_N (1, -mu t) on bd K opposite to u_T
    u = 1.5 * t;
    r = -2 * mu * t;
    r[0] = 2;
    CHECK(F::value(r, u, mu, rho).norm() <= 1e-14);
    // sticking force with a sliding velocity is no solution
    r = Vec::Zero();
    r[0] = 1;
    CHECK(F::value(r, u, mu, rho).norm() > 1e-3);
  }
  // penetration (u_N < 0, r = 0) is no solution
  r.setZero();
  u.setZero();
  u[0] = -1;
  CHECK(F::value(r, u, mu, rho).norm() > 1e-3);
}

}  // namespace

TEMPLATE_TEST_CASE("Newton one-contact functions vanish exactly at Coulomb's law", "[newton][functions]",
                   AlartCurnierFunction<Coulomb3D>, JeanMoreauFunction<Coulomb3D>,
                   NaturalMapFunction<Coulomb3D>, FischerBurmeisterFunction<Coulomb3D>,
                   AlartCurnierFunction<Coulomb2D>, FischerBurmeisterFunction<Coulomb2D>,
                   NaturalMapFunction<Frictionless>, FischerBurmeisterFunction<Frictionless>) {
  using Cone = std::conditional_t<TestType::Vec::RowsAtCompileTime == 3, Coulomb3D,
                                  std::conditional_t<TestType::Vec::RowsAtCompileTime == 2,
                                                     Coulomb2D, Frictionless>>;
  check_zeros<TestType, Cone>();
}

TEST_CASE("the natural map at rho = 1 is the error measure's residual", "[newton][functions]") {
  std::mt19937 gen(7);
  std::normal_distribution<double> normal;
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Vector3d r(normal(gen), normal(gen), normal(gen)), u(normal(gen), normal(gen), normal(gen));
    const double mu = 0.1 * (k % 12);
    CHECK((NaturalMapFunction<Coulomb3D>::value(r, u, mu, Eigen::Vector3d::Ones()) -
           natural_map<Coulomb3D>(r, u, mu)).norm() == 0.0);
  }
}

TEST_CASE("Jacobian elements match finite differences at random points", "[newton][functions]") {
  int ac_branches[3] = {0, 0, 0}, jm_branches[3] = {0, 0, 0};
  SECTION("Alart-Curnier") {
    check_random_points<AlartCurnierFunction<Coulomb3D>, Coulomb3D>(1, ac_branches);
    check_random_points<AlartCurnierFunction<Coulomb2D>, Coulomb2D>(2);
    check_random_points<AlartCurnierFunction<Frictionless>, Frictionless>(3);
    for (int b = 0; b < 3; ++b) CHECK(ac_branches[b] >= 200);  // take-off, stick, slide all hit
  }
  SECTION("Jean-Moreau") {
    check_random_points<JeanMoreauFunction<Coulomb3D>, Coulomb3D>(4, jm_branches);
    check_random_points<JeanMoreauFunction<Coulomb2D>, Coulomb2D>(5);
  }
  SECTION("natural map") {
    check_random_points<NaturalMapFunction<Coulomb3D>, Coulomb3D>(6);
    check_random_points<NaturalMapFunction<Coulomb2D>, Coulomb2D>(7);
    check_random_points<NaturalMapFunction<Frictionless>, Frictionless>(8);
  }
  SECTION("Fischer-Burmeister") {
    check_random_points<FischerBurmeisterFunction<Coulomb3D>, Coulomb3D>(9);
    check_random_points<FischerBurmeisterFunction<Coulomb2D>, Coulomb2D>(10);
    check_random_points<FischerBurmeisterFunction<Frictionless>, Frictionless>(11);
  }
}

TEST_CASE("Jacobian elements at the kinks are derivatives of an adjacent piece",
          "[newton][functions]") {
  using V = Eigen::Vector3d;
  std::mt19937 gen(12);
  const double mu = 0.5;
  const V rho(2.0, 0.5, 0.5);  // powers of two: the kink conditions hold exactly
  struct Point {
    const char* what;
    V r, u;
  };
  const Point ac_kinks[] = {
      {"x_N = 0 (contact / take-off)", V(0.6, 0.1, -0.2), V(0.3, 0.4, 0.2)},
      {"||x_T|| = R (stick / slide)", V(1.0, 0.5, 0.0), V(0.0, 0.0, 0.0)},
      {"x_N = 0, x_T = 0 (grazing)", V(0.0, 0.0, 0.0), V(0.0, 0.0, 0.0)},
      {"x_N = 0, ||x_T|| > 0 = R", V(1.0, 0.25, 0.0), V(0.5, 0.0, 0.0)},
      {"slide at r_N = 0 (JM radius kink)", V(0.0, 0.3, 0.1), V(-0.5, 1.0, 0.0)},
  };
  for (const Point& p : ac_kinks) {
    INFO(p.what);
    CHECK(Case<AlartCurnierFunction<Coulomb3D>, Coulomb3D>::matching_directions(p.r, p.u, mu, rho, gen) > 0);
    CHECK(Case<JeanMoreauFunction<Coulomb3D>, Coulomb3D>::matching_directions(p.r, p.u, mu, rho, gen) > 0);
  }
  const Point nm_kinks[] = {
      {"z on bd K", V(1.0, 0.5, 0.0), V(0.0, 0.0, 0.0)},
      {"z = 0", V(0.0, 0.0, 0.0), V(0.0, 0.0, 0.0)},
      {"z on bd of the polar cone", V(0.0, 0.0, 0.0), V(0.0, 1.0, 0.0)},
      {"u_T = 0 (De Saxce shift kink)", V(0.5, 0.1, 0.0), V(0.2, 0.0, 0.0)},
  };
  for (const Point& p : nm_kinks) {
    INFO(p.what);
    CHECK(Case<NaturalMapFunction<Coulomb3D>, Coulomb3D>::matching_directions(p.r, p.u, mu, rho, gen) > 0);
  }
  SECTION("Fischer-Burmeister at w = 0 matches the direction x = y = t e") {
    V G;
    Eigen::Matrix3d A, B;
    const V zero = V::Zero();
    FischerBurmeisterFunction<Coulomb3D>::value_and_jacobian(zero, zero, mu, rho, G, A, B);
    // x = D_mu dr = e  and  y = rho_N D_mu^-1 du~ = e  (du_T = 0: g'(0) = 0 on du_N)
    const V dr(1 / mu, 0, 0), du(mu / rho[0], 0, 0);
    const double t = 1e-6;
    const V slope = FischerBurmeisterFunction<Coulomb3D>::value(t * dr, t * du, mu, rho) / t;
    CHECK((slope - (A * du + B * dr)).norm() <= 1e-8);
  }
  SECTION("Fischer-Burmeister on bd L \\ {0}: the limit of the smoothed Jacobians") {
    // phi_eps(x, y) = x + y - (x o x + y o y + eps^2 e)^{1/2} is smooth; its
    // Jacobian tends to the element returned as eps -> 0.
    const Point fb_kinks[] = {
        {"x on bd L, y = 0 (r on bd K, u = 0)", V(1.0, 0.3, 0.4), V(0.0, 0.0, 0.0)},
        {"x = 0, y on bd L (r = 0, u~ on bd K*)", V(0.0, 0.0, 0.0), V(0.0, 0.6, 0.8)},
    };
    for (const Point& p : fb_kinks) {
      INFO(p.what);
      V G;
      Eigen::Matrix3d A, B, Afd, Bfd;
      FischerBurmeisterFunction<Coulomb3D>::value_and_jacobian(p.r, p.u, mu, rho, G, A, B);
      // eps >> sqrt(rounding of lambda1(w)) and h << eps: the differences
      // resolve the smoothed function, whose Jacobian is O(eps) from the limit.
      const double eps = 1e-4, h = 1e-9;
      // in long double: the differences divide the rounding of lambda1(w) by eps h
      auto smoothed = [&](const V& r, const V& u) {
        using LV = Eigen::Matrix<long double, 3, 1>;
        const V ut = Coulomb3D::modified_velocity(u, mu);
        const LV x(static_cast<long double>(mu) * r[0], r[1], r[2]);
        const LV y = static_cast<long double>(rho[0]) * LV(ut[0] / static_cast<long double>(mu), ut[1], ut[2]);
        const long double w0 = x.squaredNorm() + y.squaredNorm() + static_cast<long double>(eps * eps);
        const LV wb = 2 * x[0] * x + 2 * y[0] * y;  // components 1, 2 used
        const long double nb = std::sqrt(wb[1] * wb[1] + wb[2] * wb[2]);
        const long double s1 = std::sqrt(w0 - nb), s2 = std::sqrt(w0 + nb);
        LV s(0.5L * (s1 + s2), 0, 0);
        if (nb > 0) {
          s[1] = 0.5L * (s2 - s1) * wb[1] / nb;
          s[2] = 0.5L * (s2 - s1) * wb[2] / nb;
        }
        return LV(x + y - s);
      };
      for (int j = 0; j < 3; ++j) {
        const V e = V::Unit(j) * h;
        Afd.col(j) = ((smoothed(p.r, p.u + e) - smoothed(p.r, p.u - e)) / (2 * h)).cast<double>();
        Bfd.col(j) = ((smoothed(p.r + e, p.u) - smoothed(p.r - e, p.u)) / (2 * h)).cast<double>();
      }
      INFO("A\n" << A << "\nA smoothed\n" << Afd << "\nB\n" << B << "\nB smoothed\n" << Bfd);
      CHECK((A - Afd).cwiseAbs().maxCoeff() <= 1e-3);
      CHECK((B - Bfd).cwiseAbs().maxCoeff() <= 1e-3);
    }
  }
}
