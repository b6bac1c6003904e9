// ADMM with De Saxce's shift (admm.hpp): closed-form one-contact cases
// (take-off, stick, slide) on the 3D, 2D and frictionless cones, bundled
// FCLIB problems to 1e-8 (the independent error of problem/error.hpp), every
// rho strategy, over-relaxation and acceleration off, an unsymmetric W, warm
// start, budgets, callback, bad input; the same on FC/I for AdmmGlobal
// (closed-form one-contact cases, the bundled and shared FC/I files, an
// unsymmetric M through LU, bilateral constraints refused). This file is compiled with
// EIGEN_RUNTIME_NO_MALLOC and an eigen_assert that throws, so an Eigen heap
// allocation inside the iteration's FCSOLVE_NO_MALLOC bracket fails the test.
#include "throwing_eigen_assert.hpp"  // first: before Eigen

#include "test_support.hpp"

#include <fcsolve/admm.hpp>
#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/io/fclib.hpp>
#include <fcsolve/problem/error.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

using namespace fcsolve;
using fcsolve_test::make_local;
using fcsolve_test::independent_global_error;
using fcsolve_test::solve_checked;

namespace {

template <class Cone>
using DenseAdmm = Admm<Cone, DenseStorage<Cone::dim>>;
template <class Cone>
using SparseAdmm = Admm<Cone, SparseStorage<Cone::dim>>;
/// Eigen's SimplicialLDLT: its solve allocates nothing, so the whole
/// iteration, linear solve included, sits inside the no-allocation bracket.
template <class Cone>
using EigenSparseAdmm = Admm<Cone, SparseStorage<Cone::dim>, SparseAdmmFactorization<EigenBackend>>;

static_assert(satisfies_solver_contract_v<DenseAdmm<Coulomb3D>, LocalProblemView>);
static_assert(satisfies_solver_contract_v<SparseAdmm<Coulomb2D>, LocalProblemView>);
static_assert(satisfies_solver_contract_v<EigenSparseAdmm<Frictionless>, LocalProblemView>);


LocalProblem one_contact(int d, const Vector& q, double mu = 0.5) {
  DenseMatrix W = DenseMatrix::Identity(d, d);
  W(0, 0) = 2.0;  // normal stiffer than the tangent: not a multiple of I
  return make_local(d, W, q, Vector::Constant(1, mu));
}

Vector vec(std::initializer_list<double> v) {
  Vector out(Index(v.size()));
  Index i = 0;
  for (double x : v) out[i++] = x;
  return out;
}

}  // namespace

TEST_CASE("ADMM: one contact in closed form (3D, 2D, frictionless)", "[admm]") {
  SECTION("3D take-off: q_N > 0 gives r = 0") {
    DenseAdmm<Coulomb3D> admm;
    const Vector r = solve_checked(admm, one_contact(3, vec({1.0, 0.3, -0.2})));
    CHECK(admm.info().converged());
    CHECK(r.norm() <= 1e-8);
  }
  SECTION("3D sticking: u = 0, r = -W^-1 q inside the cone") {
    DenseAdmm<Coulomb3D> admm;
    const Vector r = solve_checked(admm, one_contact(3, vec({-2.0, 0.1, 0.05})));
    CHECK(admm.info().converged());
    CHECK((r - vec({1.0, -0.1, -0.05})).norm() <= 1e-7);
  }
  SECTION("3D sliding: r on the cone's edge against u_T") {
    // u_N = 2 r_N - 2 = 0: r_N = 1; r_T = -mu r_N q_T/|q_T| = (-0.5, 0); u_T = (1.5, 0)
    DenseAdmm<Coulomb3D> admm;
    const Vector r = solve_checked(admm, one_contact(3, vec({-2.0, 2.0, 0.0})));
    CHECK(admm.info().converged());
    CHECK((r - vec({1.0, -0.5, 0.0})).norm() <= 1e-7);
  }
  SECTION("2D sliding and sticking") {
    DenseAdmm<Coulomb2D> admm;
    Vector r = solve_checked(admm, one_contact(2, vec({-2.0, -3.0})));
    CHECK(admm.info().converged());
    CHECK((r - vec({1.0, 0.5})).norm() <= 1e-7);
    r = solve_checked(admm, one_contact(2, vec({-2.0, 0.2})));
    CHECK(admm.info().converged());
    CHECK((r - vec({1.0, -0.2})).norm() <= 1e-7);
  }
  SECTION("frictionless: the shift vanishes, an LCP") {
    EigenSparseAdmm<Frictionless> admm;
    const LocalProblem p = make_local(1, DenseMatrix::Identity(2, 2) * 2.0, vec({-4.0, 1.0}),
                                      Vector::Zero(2));
    const Vector r = solve_checked(admm, p);
    CHECK(admm.info().converged());
    CHECK((r - vec({2.0, 0.0})).norm() <= 1e-7);
  }
}

TEST_CASE("ADMM: many coupled contacts, 2D and frictionless, sparse storage", "[admm][nomalloc]") {
  // W = 2 I with 0.5 between neighbouring unknowns: symmetric, diagonally
  // dominant; q alternates pushes in and pulls out, with tangential drift
  for (int d : {2, 1}) {
    const Index nc = 30, m = d * nc;
    DenseMatrix W = 2.0 * DenseMatrix::Identity(m, m);
    for (Index i = 0; i + 1 < m; ++i) W(i, i + 1) = W(i + 1, i) = 0.5;
    Vector q(m);
    for (Index i = 0; i < m; ++i) q[i] = (i % d == 0) ? (i % 3 == 0 ? 0.4 : -1.0) : 0.3 * std::cos(double(i));
    const LocalProblem p = make_local(d, W, q, Vector::Constant(nc, 0.4));
    AdmmSettings s;
    s.max_iter = 20000;
    INFO("d = " << d);
    if (d == 2) {
      EigenSparseAdmm<Coulomb2D> admm(s);
      solve_checked(admm, p);
      CHECK(admm.info().converged());
    } else {
      EigenSparseAdmm<Frictionless> admm(s);
      solve_checked(admm, p);
      CHECK(admm.info().converged());
    }
  }
}

TEST_CASE("ADMM solves bundled FCLIB problems to 1e-8 without allocating", "[admm][fclib][nomalloc]") {
  for (const char* name : {"FC3D_Example1.hdf5", "Rover1039.hdf5", "OneObject-i1028-138.hdf5"}) {
    INFO(name);
    const LocalProblem p = fclib::read_local(fcsolve_test::bundled(name));
    AdmmSettings s;
    s.max_iter = 20000;
    SparseAdmm<Coulomb3D> cholmod(s);
    solve_checked(cholmod, p);
    CHECK(cholmod.info().converged());
    CHECK(local_error(p, solve_checked(cholmod, p)) <= 1e-8);
    EigenSparseAdmm<Coulomb3D> eigen(s);
    solve_checked(eigen, p);
    CHECK(eigen.info().converged());
  }
}

TEST_CASE("ADMM: every rho strategy, relaxation, acceleration off", "[admm]") {
  const LocalProblem p = fclib::read_local(fcsolve_test::bundled("Rover1039.hdf5"));
  for (AdmmRhoInit init : {AdmmRhoInit::Spectral, AdmmRhoInit::Given})
    for (AdmmRhoStrategy strategy :
         {AdmmRhoStrategy::Constant, AdmmRhoStrategy::ResidualBalancing, AdmmRhoStrategy::Osqp})
      for (bool acceleration : {true, false}) {
        INFO(to_string(init) << " " << to_string(strategy) << " acceleration " << acceleration);
        AdmmSettings s;
        s.rho_init = init;
        s.rho_strategy = strategy;
        s.acceleration = acceleration;
        s.relaxation = acceleration ? 1.0 : 1.6;
        s.max_iter = 200000;
        EigenSparseAdmm<Coulomb3D> admm(s);
        solve_checked(admm, p);
        CHECK(admm.info().converged());
        if (strategy == AdmmRhoStrategy::Constant) CHECK(admm.factorizations() == 1);
      }
}

TEST_CASE("ADMM: the extrapolation restarts when the FCLIB error doubles, even while the combined residual falls",
          "[admm]") {
  // Alg. 8's own test sees a falling combined residual and keeps
  // extrapolating with beta -> 1; the error rule restarts it.
  AdmmMomentum m(0.999);
  double combined = 1, beta = 0;
  for (int k = 0; k < 50; ++k) {
    combined *= 0.99;
    beta = m.step(combined);
    REQUIRE(beta >= 0);
  }
  CHECK(beta > 0.9);
  CHECK_FALSE(m.error_grew(1e-5));
  CHECK_FALSE(m.error_grew(0.8e-5));
  CHECK_FALSE(m.error_grew(1.5e-5));  // below twice the least, 0.8e-5
  CHECK(m.error_grew(1.7e-5));
  m = AdmmMomentum(0.999);  // what the loop does on a restart: the least error starts again
  CHECK_FALSE(m.error_grew(1.7e-5));
  CHECK(m.error_grew(3.5e-5));
}

TEST_CASE("ADMM: a cap of zero refactorisations freezes rho", "[admm]") {
  const LocalProblem p = fclib::read_local(fcsolve_test::bundled("OneObject-i1028-138.hdf5"));
  AdmmSettings s;
  s.max_refactorizations = 0;
  s.max_iter = 500;
  SparseAdmm<Coulomb3D> admm(s);
  solve_checked(admm, p);
  CHECK(admm.factorizations() <= 1);
}

TEST_CASE("ADMM: an unsymmetric W is solved as given (antisymmetric part lagged)", "[admm]") {
  DenseMatrix W(6, 6);
  W << 3, 0.4, 0.1, 1, 0, 0,   //
      0.2, 2, 0, 0, 0.5, 0,    //
      0.1, 0, 2, 0, 0, 0.3,    //
      1, 0, 0, 3, 0.3, 0,      //
      0, 0.5, 0, 0.1, 2, 0,    //
      0, 0, 0.2, 0, 0, 2;
  const LocalProblem p = make_local(3, W, vec({-1, 0.5, 0.2, -2, -0.1, 3}), vec({0.3, 0.6}));
  DenseAdmm<Coulomb3D> dense;
  solve_checked(dense, p);
  CHECK(dense.info().converged());
  EigenSparseAdmm<Coulomb3D> sparse;
  solve_checked(sparse, p);
  CHECK(sparse.info().converged());
}

TEST_CASE("ADMM: warm start from its own solution, budgets, callback, bad input", "[admm]") {
  const LocalProblem p = fclib::read_local(fcsolve_test::bundled("Rover1039.hdf5"));
  SparseAdmm<Coulomb3D> admm;
  const Vector r = solve_checked(admm, p);
  REQUIRE(admm.info().converged());
  SECTION("warm start") {
    solve_checked(admm, p, r);
    CHECK(admm.info().converged());
    CHECK(admm.info().iterations <= 2);
  }
  SECTION("max_iter") {
    admm.settings().max_iter = 3;
    solve_checked(admm, p);
    CHECK(admm.info().status == Status::MaxIterations);
    CHECK(admm.info().iterations == 3);
  }
  SECTION("max_time") {
    admm.settings().max_time = 0;
    solve_checked(admm, p);
    CHECK(admm.info().status == Status::TimeLimit);
    CHECK(admm.info().iterations == 1);
  }
  SECTION("callback") {
    int calls = 0;
    admm.settings().record_history = true;
    admm.settings().callback = [&](const IterationInfo& it) {
      ++calls;
      CHECK(it.full_error);
      return it.iteration == 4;
    };
    solve_checked(admm, p);
    CHECK(admm.info().status == Status::Stopped);
    CHECK(calls == 4);
    CHECK(admm.info().history.size() == 4);
  }
  SECTION("bad input") {
    SparseAdmm<Coulomb3D> fresh;
    Vector x(p.size()), u(p.size());
    CHECK_THROWS_AS(fresh.solve(x, u), UsageError);
    Vector short_r(2);
    CHECK_THROWS_AS(admm.solve(short_r, u), InvalidProblem);
    SparseAdmm<Coulomb2D> wrong_cone;
    CHECK_THROWS(wrong_cone.compute(p));
  }
}

// ---- AdmmGlobal: FC/I in (v, r)

namespace {

/// FC/I of one point mass: M = diag(1, 2, 2) (d = 3) or diag(1, 2) (d = 2),
/// H = I, w = 0, f = M q: W = M^-1 and q_reduced = q.
GlobalProblem one_contact_global(int d, const Vector& q, double mu = 0.5) {
  GlobalProblem g;
  g.d = d;
  Vector mass = Vector::Constant(d, 2.0);
  mass[0] = 1.0;
  g.M = DenseMatrix(mass.asDiagonal()).sparseView();
  g.H = DenseMatrix::Identity(d, d).sparseView();
  g.f = mass.cwiseProduct(q);
  g.w = Vector::Zero(d);
  g.mu = Vector::Constant(1, mu);
  g.M.makeCompressed();
  g.H.makeCompressed();
  return g;
}

/// compute + solve from r0 (zero by default); checks that the reported
/// error is the independent one and returns (r, v).
template <class Solver>
std::pair<Vector, Vector> solve_global_checked(Solver& admm, const GlobalProblem& g,
                                               Vector r0 = Vector()) {
  admm.compute(g);
  Vector r = r0.size() ? r0 : Vector(Vector::Zero(g.size())), v(g.num_dofs());
  admm.solve(r, v);
  CHECK(r.allFinite());
  CHECK(v.allFinite());
  CHECK(admm.info().error == Approx(independent_global_error(g, r, v)).epsilon(1e-6).margin(1e-13));
  return {r, v};
}

}  // namespace

TEST_CASE("ADMM on FC/I: one contact in closed form (3D, 2D)", "[admm][global]") {
  AdmmGlobal<Coulomb3D> admm;
  SECTION("take-off: q_N > 0 gives r = 0") {
    const auto [r, v] = solve_global_checked(admm, one_contact_global(3, vec({1.0, 0.3, -0.2})));
    CHECK(admm.info().converged());
    CHECK(r.norm() <= 1e-7);
  }
  SECTION("sticking: u = 0, r = -W^-1 q = -M q inside the cone") {
    const auto [r, v] = solve_global_checked(admm, one_contact_global(3, vec({-1.0, 0.1, 0.0})));
    CHECK(admm.info().converged());
    CHECK((r - vec({1.0, -0.2, 0.0})).norm() <= 1e-6);
    CHECK(v.norm() <= 1e-6);  // u = H^T v + w = v
  }
  SECTION("sliding: r_N = 1, r_T = -mu r_N on u_T's line") {
    // stick would need |r_T| = 2 q_T = 4 > mu r_N: slides, u_N = r_N - 1 = 0
    const auto [r, v] = solve_global_checked(admm, one_contact_global(3, vec({-1.0, 2.0, 0.0})));
    CHECK(admm.info().converged());
    CHECK((r - vec({1.0, -0.5, 0.0})).norm() <= 1e-6);
    CHECK(v[1] > 0);  // it slides along +t
  }
  SECTION("2D sliding") {
    AdmmGlobal<Coulomb2D> admm2;
    const auto [r, v] = solve_global_checked(admm2, one_contact_global(2, vec({-1.0, -3.0})));
    CHECK(admm2.info().converged());
    CHECK((r - vec({1.0, 0.5})).norm() <= 1e-6);
  }
}

TEST_CASE("ADMM on FC/I: the bundled and shared FC/I problems to 1e-6 without allocating",
          "[admm][global][fclib][nomalloc]") {
  // LMGC's M is unsymmetric: M + rho H H^T goes through LU there
  const std::vector<std::string> files = fcsolve_test::bundled_and_shared_files("global");
  REQUIRE(files.size() >= 3);
  for (const auto& f : files) {
    INFO(f);
    const GlobalProblem g = fclib::read_global(f);
    REQUIRE_FALSE(g.has_bilateral());
    AdmmSettings s;
    s.tol = 1e-6;
    s.max_iter = 20000;  // the catalogue's default (spheres-in-a-box: about 12000)
    s.max_time = 60;  // a guard: the largest takes about a second
    AdmmGlobal<Coulomb3D> admm(s);
    const auto [r, v] = solve_global_checked(admm, g);
    CHECK(admm.info().converged());
    CHECK(independent_global_error(g, r, v) <= 1e-6);
    // restarted from its own solution: v is recomputed from r, which moves
    // u by ADMM's dual residual; a few iterations bring it back (<= 5 measured)
    solve_global_checked(admm, g, r);
    CHECK(admm.info().converged());
    CHECK(admm.info().iterations <= 10);
  }
}

TEST_CASE("ADMM on FC/I: budgets, callback, bad input", "[admm][global]") {
  const GlobalProblem g = fclib::read_global(fcsolve_test::bundled("GFC3D_Example1.hdf5"));
  AdmmGlobal<Coulomb3D> admm;
  SECTION("max_iter") {
    admm.settings().max_iter = 3;
    solve_global_checked(admm, g);
    CHECK(admm.info().status == Status::MaxIterations);
    CHECK(admm.info().iterations == 3);
    // the rho the iterations ended with, though the factor went back to M
    // to balance the returned r
    CHECK(admm.rho() > 0);
  }
  SECTION("max_time") {
    admm.settings().max_time = 0;
    solve_global_checked(admm, g);
    CHECK(admm.info().status == Status::TimeLimit);
    CHECK(admm.info().iterations == 1);
  }
  SECTION("callback") {
    int calls = 0;
    admm.settings().callback = [&](const IterationInfo&) { return ++calls == 2; };
    solve_global_checked(admm, g);
    CHECK(admm.info().status == Status::Stopped);
    CHECK(calls == 2);
  }
  SECTION("an unreachable tolerance is never reported as converged") {
    admm.settings().tol = 1e-300;
    admm.settings().max_iter = 200;
    solve_global_checked(admm, g);
    CHECK_FALSE(admm.info().converged());
  }
  SECTION("bad input and settings") {
    AdmmGlobal<Coulomb3D> fresh;
    Vector r(g.size()), v(g.num_dofs());
    CHECK_THROWS_AS(fresh.solve(r, v), UsageError);
    admm.compute(g);
    Vector short_v(1);
    CHECK_THROWS_AS(admm.solve(r, short_v), InvalidProblem);
    AdmmGlobal<Coulomb2D> wrong_cone;
    CHECK_THROWS(wrong_cone.compute(g));
    admm.settings().rho_init = AdmmRhoInit::Spectral;
    CHECK_THROWS_AS(admm.compute(g), UsageError);
    GlobalProblem bilateral = g;
    bilateral.G = DenseMatrix::Identity(g.num_dofs(), 1).sparseView();
    bilateral.b = Vector::Zero(1);
    AdmmGlobal<Coulomb3D> plain;
    CHECK_THROWS_AS(plain.compute(bilateral), UsageError);
  }
}
