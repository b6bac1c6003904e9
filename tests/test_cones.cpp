// Cone policies: closed-form projections and property tests on 1e5 random
// vectors per cone (idempotence, membership, Moreau decomposition with an
// independently computed polar projection, orthogonality), mu = 0 to large.
#include <fcsolve/cone/cones.hpp>

#include <catch2/catch.hpp>

#include <random>

using namespace fcsolve;

namespace {

/// Projection onto the dual cone computed independently of Cone::project_dual:
/// K_mu* is the Coulomb cone of coefficient 1/mu (a half-space when mu = 0).
template <class Cone>
typename Cone::Vec dual_projection_reference(const typename Cone::Vec& z, double mu) {
  if constexpr (Cone::dim == 1) {
    return Cone::project(z, mu);
  } else {
    if (mu == 0) {
      typename Cone::Vec out = z;
      out[0] = std::max(z[0], 0.0);
      return out;
    }
    return Cone::project(z, 1.0 / mu);
  }
}

template <class Cone>
void check_cone_properties(std::uint32_t seed) {
  using Vec = typename Cone::Vec;
  std::mt19937 gen(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double mus[] = {0.0, 1e-3, 0.1, 0.3, 0.7, 1.0, 5.0, 1e3};
  const int samples = 100000;
  for (int k = 0; k < samples; ++k) {
    const double mu = (k % 9 == 8) ? 10.0 * uniform(gen) : mus[k % 8];
    Vec z;
    for (int i = 0; i < Cone::dim; ++i) z[i] = normal(gen) * std::pow(10.0, 4 * uniform(gen) - 2);
    const double scale = std::max(1.0, z.norm());
    const double tol = 1e-12 * scale;

    const Vec p = Cone::project(z, mu);
    // membership and idempotence
    REQUIRE(Cone::contains(p, mu, tol));
    REQUIRE((Cone::project(p, mu) - p).norm() <= tol);
    // Moreau: z = P_K(z) + P_{K°}(z), P_{K°}(z) = -P_{K*}(-z), orthogonal parts
    const Vec polar = -dual_projection_reference<Cone>(Vec(-z), mu);
    REQUIRE((p + polar - z).norm() <= 1e-10 * scale);
    REQUIRE(std::abs(p.dot(polar)) <= 1e-10 * scale * scale);
    REQUIRE(Cone::contains_dual(Vec(-polar), mu, 1e-10 * scale));
    // the dual projection agrees with the independent one, and is idempotent
    const Vec pd = Cone::project_dual(z, mu);
    REQUIRE((pd - dual_projection_reference<Cone>(z, mu)).norm() <= 1e-10 * scale);
    REQUIRE(Cone::contains_dual(pd, mu, tol));
    REQUIRE((Cone::project_dual(pd, mu) - pd).norm() <= tol);
    // a point of K is its own projection
    if (Cone::contains(z, mu)) REQUIRE((p - z).norm() == 0.0);
  }
}

}  // namespace

TEST_CASE("Coulomb3D projection: closed-form cases", "[cone]") {
  using V = Coulomb3D::Vec;
  const double mu = 0.5;
  // inside K: unchanged
  CHECK((Coulomb3D::project(V(2, 0.3, -0.4), mu) - V(2, 0.3, -0.4)).norm() == 0);
  // in the polar cone: 0
  CHECK(Coulomb3D::project(V(-1, 0.1, 0.1), mu).norm() == 0);
  // on the normal axis: a normal-only vector projects to itself or 0
  CHECK((Coulomb3D::project(V(3, 0, 0), mu) - V(3, 0, 0)).norm() == 0);
  CHECK(Coulomb3D::project(V(-3, 0, 0), mu).norm() == 0);
  // pure tangent (0, t, 0): a = mu t / (1 + mu^2), result (a, mu a, 0)
  const V p = Coulomb3D::project(V(0, 2, 0), mu);
  const double a = mu * 2 / (1 + mu * mu);
  CHECK(p[0] == Approx(a));
  CHECK(p[1] == Approx(mu * a));
  CHECK(p[2] == Approx(0).margin(1e-15));
  // mu = 0: K is the normal half-line
  CHECK((Coulomb3D::project(V(2, 5, -1), 0.0) - V(2, 0, 0)).norm() == 0);
  CHECK(Coulomb3D::project(V(-2, 0, 0), 0.0).norm() == 0);
  // De Saxce shift
  CHECK((Coulomb3D::de_saxce_shift(V(1, 3, 4), 0.2) - V(1.0, 0, 0)).norm() < 1e-15);
  CHECK((Coulomb3D::modified_velocity(V(1, 3, 4), 0.2) - V(2.0, 3, 4)).norm() < 1e-15);
}

TEST_CASE("Coulomb2D and frictionless projections: closed-form cases", "[cone]") {
  using V2 = Coulomb2D::Vec;
  CHECK((Coulomb2D::project(V2(1, -0.2), 0.5) - V2(1, -0.2)).norm() == 0);
  const V2 p = Coulomb2D::project(V2(0, -2), 0.5);
  CHECK(p[0] == Approx(0.5 * 2 / 1.25));
  CHECK(p[1] == Approx(-0.5 * p[0]));
  CHECK(Coulomb2D::de_saxce_shift(V2(0, -3), 0.5)[0] == Approx(1.5));
  using V1 = Frictionless::Vec;
  CHECK(Frictionless::project(V1(-1), 0.3)[0] == 0);
  CHECK(Frictionless::project(V1(2), 0.3)[0] == 2);
  CHECK(Frictionless::de_saxce_shift(V1(2), 0.3)[0] == 0);
}

TEST_CASE("Coulomb3D cone properties on 1e5 random vectors", "[cone][property]") {
  check_cone_properties<Coulomb3D>(1);
}
TEST_CASE("Coulomb2D cone properties on 1e5 random vectors", "[cone][property]") {
  check_cone_properties<Coulomb2D>(2);
}
TEST_CASE("Frictionless cone properties on 1e5 random vectors", "[cone][property]") {
  check_cone_properties<Frictionless>(3);
}

TEST_CASE("dispatch_cone picks the cone of the contact dimension", "[cone]") {
  CHECK(dispatch_cone(3, [](auto c) { return decltype(c)::dim; }) == 3);
  CHECK(dispatch_cone(2, [](auto c) { return decltype(c)::dim; }) == 2);
  CHECK(dispatch_cone(1, [](auto c) { return decltype(c)::dim; }) == 1);
  CHECK_THROWS_AS(dispatch_cone(4, [](auto c) { return decltype(c)::dim; }), InvalidProblem);
}

#include <fcsolve/cone/jordan_algebra.hpp>

TEST_CASE("Jordan algebra of the Lorentz cone", "[cone][jordan]") {
  std::mt19937 gen(11);
  std::normal_distribution<double> normal;
  for (int k = 0; k < 10000; ++k) {
    jordan::Vec<3> x, y;
    for (int i = 0; i < 3; ++i) { x[i] = normal(gen); y[i] = normal(gen); }
    const auto s = jordan::spectral<3>(x);
    // x = l1 c1 + l2 c2, c1 o c2 = 0, c_i o c_i = c_i, c1 + c2 = e
    REQUIRE((s.lambda1 * s.c1 + s.lambda2 * s.c2 - x).norm() < 1e-12);
    REQUIRE(jordan::product<3>(s.c1, s.c2).norm() < 1e-14);
    REQUIRE((jordan::product<3>(s.c1, s.c1) - s.c1).norm() < 1e-14);
    REQUIRE((jordan::arrow<3>(x) * y - jordan::product<3>(x, y)).norm() < 1e-12);
    REQUIRE(jordan::det<3>(x) == Approx(s.lambda1 * s.lambda2).margin(1e-12));
    // P(x) y = 2 x o (x o y) - (x o x) o y
    const jordan::Vec<3> Py = 2 * jordan::product<3>(x, jordan::product<3>(x, y)) -
                              jordan::product<3>(jordan::product<3>(x, x), y);
    REQUIRE((jordan::quadratic_representation<3>(x) * y - Py).norm() < 1e-10 * (1 + Py.norm()));
    if (std::abs(jordan::det<3>(x)) > 1e-3)
      REQUIRE((jordan::product<3>(x, jordan::inverse<3>(x)) - jordan::Vec<3>(1, 0, 0)).norm() <
              1e-8 * (1 + x.squaredNorm() / std::abs(jordan::det<3>(x))));
    // sqrt(x o x) = x for x in L; projection onto L = Coulomb projection with mu = 1
    const jordan::Vec<3> p = jordan::project<3>(x);
    // sqrt is not Lipschitz at the boundary: check it at interior points
    const jordan::Vec<3> q = p + jordan::Vec<3>(0.1 + p.norm(), 0, 0);
    REQUIRE((jordan::sqrt<3>(jordan::product<3>(q, q)) - q).norm() < 1e-12 * (1 + q.norm()));
    REQUIRE((p - Coulomb3D::project(x, 1.0)).norm() < 1e-12 * (1 + x.norm()));
  }
}
