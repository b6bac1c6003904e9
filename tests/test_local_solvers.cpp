// Local (one-contact) solvers: closed-form cases (take-off, stick, slide,
// mu = 0, large mu) for every solver and cone, and 10^4 random one-contact
// problems checked against the enumerative reference solver.
#include <fcsolve/nsgs.hpp>

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <random>
#include <vector>
#include <string>

using namespace fcsolve;

namespace {

/// Runs a local solver on (W, q, mu) from r = 0. One-step solvers (the
/// projection) are iterated as the NSGS would iterate them on one contact.
template <class Local>
typename Local::Vec run_local(const SmallMatrix<Local::Cone::dim>& W, const typename Local::Vec& q,
                              double mu, const typename Local::Settings& s = {},
                              int repeats = 1) {
  const auto data = Local::prepare(W, mu, s);
  typename Local::Vec r = Local::Vec::Zero();
  for (int k = 0; k < repeats; ++k) Local::solve(data, q, r, s);
  return r;
}

template <class Cone>
double residual(const SmallMatrix<Cone::dim>& W, const typename Cone::Vec& q, double mu,
                const typename Cone::Vec& r) {
  return local::OneContact<Cone>::residual(W, q, mu, r);
}

/// One-step solvers need many repeats to reach the fixed point.
template <template <class> class Local>
int repeats_for() {
  return std::is_same_v<Local<Coulomb3D>, local::Projection<Coulomb3D>> ? 2000 : 1;
}

template <template <class> class LocalTpl>
void check_closed_form_3d(const std::string& name) {
  INFO(name);
  using Local = LocalTpl<Coulomb3D>;
  using V = Eigen::Vector3d;
  const Eigen::Matrix3d W = V(2, 1, 1).asDiagonal();
  const int n = repeats_for<LocalTpl>();
  {
    INFO("take-off: q_N > 0 gives r = 0, u = q");
    const V r = run_local<Local>(W, V(1, 0.3, -0.2), 0.5, {}, n);
    CHECK(r.norm() <= 1e-12);
  }
  {
    INFO("stick: u = 0, r = -W^-1 q strictly inside K");
    const V q(-2, 0.1, 0.1), r = run_local<Local>(W, q, 0.5, {}, n);
    CHECK((r - V(1, -0.1, -0.1)).norm() <= 1e-9);
    CHECK((W * r + q).norm() <= 1e-9);
  }
  {
    INFO("slide: r on the boundary, r_T opposed to u_T, u_N = 0");
    const V q(-2, 3, 0), r = run_local<Local>(W, q, 0.5, {}, n);
    CHECK((r - V(1, -0.5, 0)).norm() <= 1e-9);  // u = (0, 2.5, 0)
    const V u = W * r + q;
    CHECK(std::abs(u[0]) <= 1e-9);
    CHECK(u[1] > 0);
  }
  {
    INFO("slide with a coupled, unsymmetric block");
    Eigen::Matrix3d Wc;
    Wc << 3, 0.4, -0.2, 0.3, 2, 0.1, -0.1, 0.2, 1.5;
    const V q(-1, 2, -1.5), r = run_local<Local>(Wc, q, 0.3, {}, n);
    CHECK(residual<Coulomb3D>(Wc, q, 0.3, r) <= 1e-9);
    CHECK(std::abs(r.tail<2>().norm() - 0.3 * r[0]) <= 1e-9);  // on the boundary
  }
  {
    INFO("mu = 0: normal contact only");
    const V q(-2, 3, -1), r = run_local<Local>(W, q, 0.0, {}, n);
    CHECK((r - V(1, 0, 0)).norm() <= 1e-9);
  }
  {
    INFO("large mu: the slide case sticks");
    const V q(-2, 3, 0), r = run_local<Local>(W, q, 10.0, {}, n);
    CHECK((r - V(1, -3, 0)).norm() <= 1e-9);
  }
}

template <template <class> class LocalTpl>
void check_closed_form_2d_and_frictionless(const std::string& name) {
  INFO(name);
  using Local2 = LocalTpl<Coulomb2D>;
  using Local1 = LocalTpl<Frictionless>;
  const int n = repeats_for<LocalTpl>();
  using V2 = Eigen::Vector2d;
  const Eigen::Matrix2d W2 = V2(2, 1).asDiagonal();
  CHECK(run_local<Local2>(W2, V2(1, -3), 0.5, {}, n).norm() <= 1e-12);                   // take-off
  CHECK((run_local<Local2>(W2, V2(-2, 0.2), 0.5, {}, n) - V2(1, -0.2)).norm() <= 1e-9);  // stick
  CHECK((run_local<Local2>(W2, V2(-2, 3), 0.5, {}, n) - V2(1, -0.5)).norm() <= 1e-9);    // slide
  CHECK((run_local<Local2>(W2, V2(-2, -3), 0.5, {}, n) - V2(1, 0.5)).norm() <= 1e-9);    // slide
  using V1 = SmallVector<1>;
  const SmallMatrix<1> W1 = SmallMatrix<1>::Constant(4);
  CHECK(run_local<Local1>(W1, V1(2), 0, {}, n)[0] == 0);                     // LCP, r = 0
  CHECK(run_local<Local1>(W1, V1(-2), 0, {}, n)[0] == Approx(0.5).epsilon(1e-12));  // r = -q / W
}

/// A random one-contact problem: W = A A^T + eps I (SPD, condition up to
/// about 1e4), in a quarter of the cases plus a skew-symmetric part (W stays
/// positive definite, as FCLIB's slightly unsymmetric blocks are), and a
/// random q.
struct RandomContact {
  Eigen::Matrix3d W;
  Eigen::Vector3d q;
  double mu;
};

RandomContact random_contact(std::mt19937& gen) {
  std::uniform_real_distribution<double> uni(-1, 1), pos(0, 1);
  RandomContact c;
  Eigen::Matrix3d A;
  for (int i = 0; i < 9; ++i) A(i / 3, i % 3) = uni(gen);
  c.W = A * A.transpose() + (1e-3 + 0.2 * pos(gen)) * Eigen::Matrix3d::Identity();
  if (pos(gen) < 0.25) {
    Eigen::Matrix3d E;
    for (int i = 0; i < 9; ++i) E(i / 3, i % 3) = uni(gen);
    c.W += 0.05 * c.W.norm() * (E - E.transpose());
  }
  c.W *= std::pow(10.0, 3 * uni(gen));  // scale: 1e-3 ... 1e3
  for (int i = 0; i < 3; ++i) c.q[i] = uni(gen);
  c.q[0] -= 0.3;  // mostly active contacts
  const double pick = pos(gen);
  c.mu = pick < 0.05 ? 0.0 : pick < 0.9 ? pos(gen) : 1 + 9 * pos(gen);
  return c;
}

/// Every local solver must return a solution (residual at rounding level,
/// relative to the data) and, where the reference finds exactly one, the
/// same one.
template <class Local>
void check_random_against_reference(const std::string& name, const typename Local::Settings& s,
                                    int count, int repeats, double tol, int allowed_failures = 0) {
  INFO(name);
  using Reference = local::Enumerative<Coulomb3D>;
  Reference::Settings ref_settings;
  ref_settings.newton_first = false;
  std::mt19937 gen(20250611);
  int unique = 0, failures = 0, mismatches = 0;
  for (int k = 0; k < count; ++k) {
    const RandomContact c = random_contact(gen);
    const auto ref_data = Reference::prepare(c.W, c.mu, ref_settings);
    const Reference::Solutions all = Reference::enumerate(ref_data, c.q, ref_settings);
    const Eigen::Vector3d r = run_local<Local>(c.W, c.q, c.mu, s, repeats);
    const double scale = std::max(c.q.norm(), c.W.norm() * r.norm());
    if (!(residual<Coulomb3D>(c.W, c.q, c.mu, r) <= tol * scale)) ++failures;
    if (all.count == 1) {
      ++unique;
      if (!((r - all.r[0]).norm() <= 1e3 * tol * std::max(1.0, all.r[0].norm()))) ++mismatches;
    }
  }
  CHECK(failures <= allowed_failures);
  CHECK(mismatches <= allowed_failures);
  CHECK(unique > count / 2);  // the comparison is not vacuous
}

}  // namespace

TEST_CASE("enumerative reference finds every branch", "[local]") {
  using E = local::Enumerative<Coulomb3D>;
  E::Settings s;
  s.newton_first = false;
  const Eigen::Matrix3d W = Eigen::Vector3d(2, 1, 1).asDiagonal();
  const auto d = E::prepare(W, 0.5, s);
  auto sol = E::enumerate(d, Eigen::Vector3d(1, 0.3, -0.2), s);
  REQUIRE(sol.count == 1);
  CHECK(sol.kind[0] == local::ContactCase::TakeOff);
  sol = E::enumerate(d, Eigen::Vector3d(-2, 0.1, 0.1), s);
  REQUIRE(sol.count == 1);
  CHECK(sol.kind[0] == local::ContactCase::Stick);
  sol = E::enumerate(d, Eigen::Vector3d(-2, 3, 0), s);
  REQUIRE(sol.count == 1);
  CHECK(sol.kind[0] == local::ContactCase::Slide);
  CHECK((sol.r[0] - Eigen::Vector3d(1, -0.5, 0)).norm() <= 1e-12);
}

TEST_CASE("real roots of polynomials up to degree 4", "[local]") {
  const auto roots_of = [](std::array<double, 5> c, int degree) {
    local::Polynomial p;
    p.c = c;
    p.degree = degree;
    std::array<double, 4> r;
    const int n = local::real_roots(p, r);
    return std::vector<double>(r.begin(), r.begin() + n);
  };
  // (x - 1)(x - 2)(x + 3)(x - 0.5) = x^4 - 0.5 x^3 - 7 x^2 + 9.5 x - 3
  auto r = roots_of({-3, 9.5, -7, -0.5, 1}, 4);
  REQUIRE(r.size() == 4);
  CHECK(r[0] == Approx(-3).epsilon(1e-14));
  CHECK(r[1] == Approx(0.5).epsilon(1e-14));
  CHECK(r[2] == Approx(1).epsilon(1e-14));
  CHECK(r[3] == Approx(2).epsilon(1e-14));
  // (x - 1)^2 (x + 2) = x^3 - 3 x + 2: the double root is found
  r = roots_of({2, -3, 0, 1, 0}, 3);
  REQUIRE(r.size() == 2);
  CHECK(r[0] == Approx(-2).epsilon(1e-14));
  CHECK(r[1] == Approx(1).epsilon(1e-7));
  // x^2 + 1: none; a vanishing leading coefficient lowers the degree
  CHECK(roots_of({1, 0, 1, 0, 0}, 2).empty());
  r = roots_of({-2, 1, 0, 0, 1e-300}, 4);
  REQUIRE(r.size() == 1);
  CHECK(r[0] == Approx(2));
}

TEST_CASE("sliding equation: the quartic's roots are the zeros of f", "[local]") {
  std::mt19937 gen(3);
  for (int k = 0; k < 200; ++k) {
    const RandomContact c = random_contact(gen);
    const local::SlidingEquation f(c.W, c.q, std::max(c.mu, 0.1));
    std::array<local::SlidingEquation::Vec2, 5> t;
    const int n = f.roots(t, 20);
    // f(th) = a1 s - a2 c + ...: sample it and count the sign changes
    int changes = 0;
    const int samples = 4000;
    double prev = f.value({1, 0});
    for (int i = 1; i <= samples; ++i) {
      const double th = 2 * M_PI * i / samples;
      const double v = f.value({std::cos(th), std::sin(th)});
      if ((v > 0) != (prev > 0)) ++changes;
      prev = v;
    }
    const double scale = std::abs(f.a1) + std::abs(f.a2) + std::abs(f.A) + std::abs(f.B) + std::abs(f.C);
    int zeros = 0;
    for (int i = 0; i < n; ++i)
      if (std::abs(f.value(t[i])) <= 1e-10 * scale) ++zeros;
    CHECK(zeros >= std::min(changes, 4));
  }
}

TEST_CASE("fast enumerative: a direction run ending on an anti-parallel root is restarted from -t",
          "[local]") {
  // A corner of a sliding cube (bench_nsgs nsgs-small/cube-4) in mid-solve.
  // f(t) = 0 has a root where u_T points against t, which is not a
  // solution; a warm start 0.1 rad from it leads the direction iteration
  // (SlidingEquation::halley) there.
  using E = local::Enumerative<Coulomb3D>;
  using Vec2 = local::SlidingEquation::Vec2;
  Eigen::Matrix3d W;
  W << 4, -1.5, 1.5, -1.5, 4, 1.5, 1.5, 1.5, 4;
  const Eigen::Vector3d q(-0.053054385457392675, 0.052485170951347616, -0.020454054322373131);
  const double mu = 0.3;
  const local::SlidingEquation f(W, q, mu);
  std::array<Vec2, 5> roots;
  const int n = f.roots(roots, 30);
  int spurious = -1;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d r = local::SlidingEquation::reaction(W, q, mu, roots[k]);
    if (r[0] > 0 && (W * r + q).tail<2>().dot(roots[k]) < 0) spurious = k;
  }
  REQUIRE(spurious >= 0);
  const Vec2 ts = roots[spurious];
  const double c = std::cos(0.1), sn = std::sin(0.1);
  const Vec2 t_warm(c * ts[0] - sn * ts[1], sn * ts[0] + c * ts[1]);
  const double rn = local::SlidingEquation::reaction(W, q, mu, ts)[0];
  const Eigen::Vector3d warm(rn, -mu * rn * t_warm[0], -mu * rn * t_warm[1]);
  Vec2 t = t_warm;
  REQUIRE(f.halley(t, 30));
  CHECK((t - ts).norm() <= 1e-12);
  const Eigen::Vector3d wrong = local::SlidingEquation::reaction(W, q, mu, t);
  CHECK((W * wrong + q).tail<2>().dot(t) < 0);
  CHECK(residual<Coulomb3D>(W, q, mu, wrong) > 1e-3 * q.norm());
  // from the opposite direction it reaches the solution, to rounding
  t = -t;
  REQUIRE(f.halley(t, 30));
  CHECK(residual<Coulomb3D>(W, q, mu, local::SlidingEquation::reaction(W, q, mu, t)) <= 1e-15);
  // the fast solve from that warm start returns that slide, the reference's
  // only solution
  E::Settings s, ref;
  ref.newton_first = false;
  const E::Solutions all = E::enumerate(E::prepare(W, mu, ref), q, ref);
  REQUIRE(all.count == 1);
  Eigen::Vector3d r = warm;
  const local::LocalResult res = E::solve(E::prepare(W, mu, s), q, r, s);
  CHECK(res.converged);
  CHECK(res.kind == local::ContactCase::Slide);
  CHECK((r - all.r[0]).norm() <= 1e-14);
}

TEST_CASE("local solvers: closed-form one-contact cases, 3D", "[local]") {
  check_closed_form_3d<local::Projection>("projection");
  check_closed_form_3d<local::ProjectionIterative>("projection-iterative");
  check_closed_form_3d<local::Enumerative>("enumerative");
  check_closed_form_3d<local::AlartCurnierNewton>("alart-curnier newton");
  check_closed_form_3d<local::FischerBurmeisterNewton>("fischer-burmeister newton");
  check_closed_form_3d<local::Hybrid>("hybrid");
}

TEST_CASE("local Newton solvers reach the sliding solution without the closed forms", "[local]") {
  // closed_form_first = false: Newton alone, from r = 0, on the cases the
  // closed forms would otherwise answer
  const Eigen::Matrix3d W = Eigen::Vector3d(2, 1, 1).asDiagonal();
  const auto check = [&](auto solver, const char* name) {
    using L = decltype(solver);
    INFO(name);
    typename L::Settings s;
    s.closed_form_first = false;
    for (const Eigen::Vector3d& q : {Eigen::Vector3d(1, 0.3, -0.2), Eigen::Vector3d(-2, 0.1, 0.1),
                                    Eigen::Vector3d(-2, 3, 0)}) {
      const Eigen::Vector3d r = run_local<L>(W, q, 0.5, s);
      CHECK(residual<Coulomb3D>(W, q, 0.5, r) <= 1e-10);
    }
  };
  check(local::AlartCurnierNewton<Coulomb3D>(), "alart-curnier");
  check(local::FischerBurmeisterNewton<Coulomb3D>(), "fischer-burmeister");
}

TEST_CASE("local solvers: 2D and frictionless through the same template", "[local]") {
  check_closed_form_2d_and_frictionless<local::Projection>("projection");
  check_closed_form_2d_and_frictionless<local::ProjectionIterative>(
      "projection-iterative");
  check_closed_form_2d_and_frictionless<local::Enumerative>("enumerative");
  check_closed_form_2d_and_frictionless<local::AlartCurnierNewton>("alart-curnier newton");
  check_closed_form_2d_and_frictionless<local::FischerBurmeisterNewton>("fischer-burmeister newton");
  check_closed_form_2d_and_frictionless<local::Hybrid>("hybrid");
}

TEST_CASE("local solvers agree with the enumerative reference on 10^4 random contacts",
          "[local][random]") {
  check_random_against_reference<local::Enumerative<Coulomb3D>>(
      "enumerative, fast mode", {}, 10000, 1, 1e-9);
  local::ProjectionIterative<Coulomb3D>::Settings it;
  it.max_iter = 100000;
  it.tol = 1e-13;
  check_random_against_reference<local::ProjectionIterative<Coulomb3D>>(
      "projection-iterative", it, 10000, 1, 1e-9);
  check_random_against_reference<local::Hybrid<Coulomb3D>>("hybrid", {}, 10000, 1, 1e-9);
  check_random_against_reference<local::FischerBurmeisterNewton<Coulomb3D>>(
      "fischer-burmeister newton", {}, 10000, 1, 1e-9);
  // Alart-Curnier Newton cycles on a few of these (5 in 10^4 at the time of
  // writing, large mu times N-T coupling): what the hybrid is for
  check_random_against_reference<local::AlartCurnierNewton<Coulomb3D>>(
      "alart-curnier newton", {}, 10000, 1, 1e-9, 10);
}
