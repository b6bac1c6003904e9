// Local (one-contact) solvers: closed-form cases (take-off, stick, slide,
// mu = 0, large mu) for every solver and cone, and 10^4 random one-contact
// problems checked against the enumerative reference solver.
#include <fcsolve/nsgs.hpp>

#include <catch2/catch.hpp>

#include <random>
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
                                    int count, int repeats, double tol) {
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
  CHECK(failures == 0);
  CHECK(mismatches == 0);
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

TEST_CASE("local solvers: closed-form one-contact cases, 3D", "[local]") {
  check_closed_form_3d<local::Projection>("projection");
  check_closed_form_3d<local::ProjectionIterative>("projection-iterative");
  check_closed_form_3d<local::Enumerative>("enumerative");
}

TEST_CASE("local solvers: 2D and frictionless through the same template", "[local]") {
  check_closed_form_2d_and_frictionless<local::Projection>("projection");
  check_closed_form_2d_and_frictionless<local::ProjectionIterative>(
      "projection-iterative");
  check_closed_form_2d_and_frictionless<local::Enumerative>("enumerative");
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
}
