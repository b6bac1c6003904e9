// The proximal point method (ppa.hpp): closed-form one-contact cases
// (take-off, stick, slide) with both inner solvers, 2D and frictionless
// cones, every FCLIB local problem to 1e-8 (checked with the independent
// error of problem/error.hpp), rank-deficient scenes (one rigid box on eight
// contacts: rank W = 6 of 24; a settled sphere pile, `fcsolve generate
// sphere-pile`'s scene), warm start, budgets, callback, bad input,
// the regularised subproblem itself and the catalogue entries; ppa-global
// (ProximalPointGlobal) on the FC/I files and the global Newton's contact
// compliance it relies on.
#include "test_support.hpp"

#include <fcsolve/problem/error.hpp>
#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/io/fclib.hpp>
#include <fcsolve/ppa.hpp>
#include <fcsolve/scenes/rigid_stepper.hpp>
#include <fcsolve/scenes/sphere_pile.hpp>
#include "test_catalogue.hpp"

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <random>
#include <set>
#include <vector>

using namespace fcsolve;

namespace {

template <class Cone>
using PpaNewton = ProximalPoint<Cone, Newton<AlartCurnierFunction, Cone, DenseStorage<Cone::dim>>>;
template <class Cone>
using PpaNsgs = ProximalPoint<Cone, Nsgs<Cone, DenseStorage<Cone::dim>>>;

static_assert(satisfies_solver_contract_v<ProximalPoint<Coulomb3D>, LocalProblemView>);
static_assert(satisfies_solver_contract_v<PpaNsgs<Coulomb2D>, LocalProblemView>);
static_assert(satisfies_solver_contract_v<PpaNewton<Frictionless>, LocalProblemView>);
static_assert(satisfies_solver_contract_v<ProximalPointGlobal<Coulomb3D>, GlobalProblemView>);

using fcsolve_test::make_local;
using fcsolve_test::solve_checked;


/// Random well-posed problem: W = H^T H / n with H of n = m + 5 rows.
LocalProblem random_problem(int d, Index nc, double mu, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> normal;
  const Index m = d * nc, n = m + 5;
  DenseMatrix H(n, m);
  for (Index i = 0; i < n; ++i)
    for (Index j = 0; j < m; ++j) H(i, j) = normal(gen);
  Vector q(m);
  for (Index i = 0; i < m; ++i) q[i] = normal(gen) - (i % d == 0 ? 0.5 : 0.0);
  return make_local(d, H.transpose() * H / double(n), q, Vector::Constant(nc, mu));
}

/// One rigid unit cube (mass 1, inertia 1/6) on the ground, touching it at
/// its four bottom corners and four bottom edge midpoints, thrown sideways
/// and spinning: W = H^T M^-1 H is 24 x 24 of rank 6, the rank deficiency
/// of piles and stacks (many contacts per body). Contact frame (n, t1, t2)
/// = (z, x, y); H's column for direction e at point p is (e, p x e).
LocalProblem box_on_eight_contacts(double mu) {
  const std::vector<Eigen::Vector3d> points = {{-0.5, -0.5, -0.5}, {0.5, -0.5, -0.5}, {-0.5, 0.5, -0.5},
                                               {0.5, 0.5, -0.5},   {0.0, -0.5, -0.5}, {0.0, 0.5, -0.5},
                                               {-0.5, 0.0, -0.5},  {0.5, 0.0, -0.5}};
  const Index nc = Index(points.size());
  DenseMatrix H(6, 3 * nc);
  const Eigen::Vector3d frame[3] = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(),
                                    Eigen::Vector3d::UnitY()};
  for (Index a = 0; a < nc; ++a)
    for (int k = 0; k < 3; ++k) {
      H.col(3 * a + k).head<3>() = frame[k];
      H.col(3 * a + k).tail<3>() = points[std::size_t(a)].cross(frame[k]);
    }
  Vector Minv(6);
  Minv << 1, 1, 1, 6, 6, 6;
  Vector v_free(6);  // falling, sliding along x and y, spinning about z
  v_free << 1.0, 0.5, -1.0, 0.1, -0.05, 0.3;
  return make_local(3, H.transpose() * Minv.asDiagonal() * H, H.transpose() * v_free,
                    Vector::Constant(nc, mu));
}

}  // namespace

TEST_CASE("ppa: closed-form one-contact solutions (3D), Newton and NSGS inner", "[ppa][closed-form]") {
  const DenseMatrix W = Eigen::Vector3d(2, 1, 1).asDiagonal();
  auto run = [&](const Vector& q) {
    const LocalProblem p = make_local(3, W, q, Vector::Constant(1, 0.5));
    PpaNewton<Coulomb3D> newton;
    newton.settings().tol = 1e-12;
    const Vector r = solve_checked(newton, p);
    CHECK(newton.info().converged());
    CHECK(local_error(p, r) <= 1e-12);
    PpaNsgs<Coulomb3D> nsgs;
    nsgs.settings().tol = 1e-12;
    CHECK((solve_checked(nsgs, p) - r).norm() <= 1e-10);
    CHECK(nsgs.info().converged());
    return r;
  };
  SECTION("take-off: q_N > 0, r = 0") { CHECK(run(Eigen::Vector3d(1, 0.3, -0.2)).norm() <= 1e-12); }
  SECTION("stick: r = -W^-1 q inside the cone, u = 0") {
    CHECK((run(Eigen::Vector3d(-2, 0.1, 0.1)) - Eigen::Vector3d(1, -0.1, -0.1)).norm() <= 1e-11);
  }
  SECTION("slide: r_N = 1, r_T = -mu r_N u_T / ||u_T||") {
    // W = diag(2,1,1), q = (-2, 3, 4): u_T = q_T + r_T = (3, 4) (1 - mu / 5)
    CHECK((run(Eigen::Vector3d(-2, 3, 4)) - Eigen::Vector3d(1, -0.3, -0.4)).norm() <= 1e-11);
  }
}

TEST_CASE("ppa: 2D and frictionless cones through the same template", "[ppa][closed-form]") {
  SECTION("2D slide: W = I, q = (-1, 2), mu = 0.5 -> r = (1, -0.5)") {
    const LocalProblem p =
        make_local(2, DenseMatrix::Identity(2, 2), Eigen::Vector2d(-1, 2), Vector::Constant(1, 0.5));
    PpaNewton<Coulomb2D> ppa;
    ppa.settings().tol = 1e-12;
    CHECK((solve_checked(ppa, p) - Eigen::Vector2d(1, -0.5)).norm() <= 1e-11);
    CHECK(ppa.info().converged());
  }
  SECTION("frictionless LCP: W = [[2, 1], [1, 2]], q = (-3, 1) -> r = (1.5, 0)") {
    DenseMatrix W(2, 2);
    W << 2, 1, 1, 2;
    const LocalProblem p = make_local(1, W, Eigen::Vector2d(-3, 1), Vector::Zero(2));
    PpaNewton<Frictionless> ppa;
    ppa.settings().tol = 1e-12;
    CHECK((solve_checked(ppa, p) - Eigen::Vector2d(1.5, 0)).norm() <= 1e-11);
    CHECK(ppa.info().converged());
    PpaNsgs<Frictionless> nsgs;
    nsgs.settings().tol = 1e-12;
    CHECK((solve_checked(nsgs, p) - Eigen::Vector2d(1.5, 0)).norm() <= 1e-11);
  }
  SECTION("random coupled 2D and frictionless problems, sparse storage") {
    const LocalProblem p2 = random_problem(2, 30, 0.4, 1), p1 = random_problem(1, 40, 0.0, 2);
    ProximalPoint<Coulomb2D> ppa2;
    CHECK(local_error(p2, solve_checked(ppa2, p2)) <= 1e-8);
    CHECK(ppa2.info().converged());
    ProximalPoint<Frictionless> ppa1;
    const Vector r = solve_checked(ppa1, p1);
    CHECK(ppa1.info().converged());
    CHECK(local_error(p1, r) <= 1e-8);
    const Vector u = SparseMatrix(p1.W) * r + p1.q;
    CHECK(r.minCoeff() >= -1e-12 * r.norm());
    CHECK(u.minCoeff() >= -1e-8 * p1.q.norm());
  }
}

TEST_CASE("ppa: every FCLIB local problem to 1e-8 (independent error)", "[ppa][fclib]") {
  const auto files = fcsolve_test::fclib_files("local");
  REQUIRE(files.size() >= 3);
  for (const auto& f : files) {
    INFO(f);
    const LocalProblem p = fclib::read_local(f);
    ProximalPoint<Coulomb3D> ppa;
    ppa.settings().max_time = 60;  // a generous guard; each takes well under a second
    const Vector r = solve_checked(ppa, p);
    CHECK(ppa.info().status == Status::Converged);
    CHECK(local_error(p, r) <= 1e-8);
  }
}

TEST_CASE("ppa: a rank-deficient W (one box on eight contacts)", "[ppa][rank-deficient]") {
  const LocalProblem p = box_on_eight_contacts(0.3);
  const Eigen::FullPivLU<DenseMatrix> lu{DenseMatrix(p.W)};
  REQUIRE(lu.rank() == 6);  // 24 unknowns, 6 degrees of freedom
  for (double mu : {0.3, 0.0, 1.0}) {
    INFO("mu = " << mu);
    const LocalProblem q = box_on_eight_contacts(mu);
    ProximalPoint<Coulomb3D> ppa;
    const Vector r = solve_checked(ppa, q);
    CHECK(ppa.info().converged());
    CHECK(local_error(q, r) <= 1e-8);
    // the box is held: the total normal reaction stops its fall
    double total_normal = 0;
    for (Index a = 0; a < q.num_contacts(); ++a) total_normal += r[3 * a];
    CHECK(total_normal > 0);
    ProximalPoint<Coulomb3D, Nsgs<Coulomb3D, BlockSparseStorage<3>>> nsgs;
    CHECK(local_error(q, solve_checked(nsgs, q)) <= 1e-8);
    CHECK(nsgs.info().converged());
  }
}

TEST_CASE("ppa: a settled sphere pile (rank-deficient W)", "[ppa][rank-deficient]") {
  // the scene of `fcsolve generate sphere-pile` (cli/generate.cpp's step
  // settings): stepped until ~1.5 contacts per sphere
  scenes::SpherePileLayout layout;
  layout.spheres = 60;
  scenes::SpherePile pile(layout);
  scenes::StepSettings s;
  s.h = 5e-3;
  s.law.beta = 0;  // --penetration-correction 0
  s.law.slop = 0;
  s.tol = 1e-4;
  s.max_iter = 50;
  scenes::RigidStepper<scenes::SpherePile> stepper(pile, s);
  LocalProblem p;
  for (int k = 0; k < 600 && p.num_contacts() < 90; ++k)
    if (stepper.step().contacts >= 60) p = stepper.local();
  REQUIRE(p.num_contacts() >= 60);
  Eigen::FullPivLU<DenseMatrix> lu{DenseMatrix(p.W)};
  lu.setThreshold(1e-10);
  INFO("nc = " << p.num_contacts() << ", m = " << p.size() << ", rank W = " << lu.rank());
  CHECK(lu.rank() < p.size());  // closed loops of contacts between spheres
  ProximalPoint<Coulomb3D> ppa;
  ppa.settings().max_time = 60;  // a guard; it takes well under a second
  const Vector r = solve_checked(ppa, p);
  CHECK(ppa.info().converged());
  CHECK(local_error(p, r) <= 1e-8);
}

TEST_CASE("ppa: warm start, budgets, callback and history", "[ppa][api]") {
  const LocalProblem p = fclib::read_local(fcsolve_test::bundled("Capsules-i101-404.hdf5"));
  ProximalPoint<Coulomb3D> ppa;
  ppa.compute(p);
  Vector r = Vector::Zero(p.size()), u(p.size());
  SECTION("restarted from its own solution it converges at once") {
    ppa.solve(r, u);
    REQUIRE(ppa.info().converged());
    const Vector first = r;
    ppa.solve(r, u);
    CHECK(ppa.info().converged());
    CHECK(ppa.info().iterations <= 2);
    CHECK(local_error(p, r) <= 1e-8);
    // and from a perturbed solution it still converges, in few subproblems
    Vector near = first;
    near *= 1.01;
    ppa.solve(near, u);
    CHECK(ppa.info().converged());
    CHECK(local_error(p, near) <= 1e-8);
  }
  SECTION("iteration budget: the best iterate and its true error") {
    ppa.settings().max_iter = 1;
    ppa.solve(r, u);
    CHECK(ppa.info().status == Status::MaxIterations);
    CHECK(ppa.info().iterations == 1);
    CHECK(ppa.info().error == Approx(local_error(p, r)).epsilon(1e-9));
  }
  SECTION("time budget: 0 returns the warm start at once") {
    ppa.settings().max_time = 0;
    ppa.solve(r, u);
    CHECK(ppa.info().status == Status::TimeLimit);
    CHECK(ppa.info().iterations == 0);
    CHECK(r.isZero());
  }
  SECTION("an unreachable tolerance is never reported as converged") {
    ppa.settings().tol = 1e-300;
    ppa.settings().max_iter = 30;
    ppa.solve(r, u);
    CHECK_FALSE(ppa.info().converged());
    CHECK(ppa.info().error == Approx(local_error(p, r)).epsilon(1e-9));
  }
  SECTION("the callback sees every outer iteration's full error and can stop the solve") {
    std::vector<IterationInfo> seen;
    ppa.settings().record_history = true;
    ppa.settings().tol = 1e-14;
    ppa.settings().callback = [&](const IterationInfo& it) {
      seen.push_back(it);
      return it.iteration >= 2;  // true stops
    };
    ppa.solve(r, u);
    CHECK(ppa.info().status == Status::Stopped);
    REQUIRE(seen.size() == 2);
    CHECK(seen.back().iteration == 2);
    CHECK(seen.front().full_error);
    CHECK(ppa.info().history.size() == 2);
    CHECK(ppa.info().history.back() == Approx(local_error(p, r)).epsilon(1e-9));
  }
}

TEST_CASE("ppa: bad input and settings are typed errors", "[ppa][api]") {
  const LocalProblem p = fclib::read_local(fcsolve_test::bundled("Rover1039.hdf5"));
  ProximalPoint<Coulomb3D> ppa;
  Vector r, u;
  fcsolve_test::check_contract_errors(ppa, p, r, u);
  ppa.settings().alpha_min = 0;
  CHECK_THROWS_AS(ppa.solve(r, u), UsageError);
  const LocalProblem two_d =
      make_local(2, DenseMatrix::Identity(2, 2), Eigen::Vector2d(-1, 0), Vector::Constant(1, 0.3));
  CHECK_THROWS_AS(ppa.compute(two_d), InvalidProblem);
}

TEST_CASE("ppa: the proximal subproblem shifts W's diagonal and q in place", "[ppa][subproblem]") {
  // W with a missing diagonal entry: the copy stores it
  DenseMatrix W = DenseMatrix::Zero(3, 3);
  W(0, 0) = 2;
  W(1, 2) = W(2, 1) = 0.5;
  const LocalProblem p = make_local(3, W, Eigen::Vector3d(-1, 0.2, 0.1), Vector::Constant(1, 0.4));
  ProximalProblem prox;
  prox.compute(p);
  CHECK(prox.diagonal_scale() == Approx(2.0 / 3));
  const double* values = prox.view().W.valuePtr();
  prox.set_alpha(0.25);
  const Eigen::Vector3d c(1, -1, 2);
  prox.set_centre(c);
  CHECK(prox.view().W.valuePtr() == values);  // rewritten in place
  const DenseMatrix expected = W + 0.25 * DenseMatrix::Identity(3, 3);
  CHECK((DenseMatrix(SparseMatrix(prox.view().W)) - expected).norm() == 0);
  CHECK((Vector(prox.view().q) - (p.q - 0.25 * c)).norm() <= 1e-15);
  CHECK(SparseMatrix(prox.view().W).nonZeros() == 5);
}

TEST_CASE("ppa: Newton's compute() on a subproblem of the same pattern rereads only the values",
          "[ppa][subproblem]") {
  // The outer loop hands the inner Newton W + alpha I with a new alpha each
  // time: the second compute() must solve the new values (not the old ones),
  // as a solver computed afresh does.
  const auto files = fcsolve_test::fclib_files("local");
  REQUIRE(!files.empty());
  const LocalProblem p = fclib::read_local(files.front());
  ProximalProblem prox;
  prox.compute(p);
  const Vector centre = Vector::Zero(p.size());
  using SparseNewton = Newton<AlartCurnierFunction, Coulomb3D, SparseStorage<3>>;
  SparseNewton reused;
  for (const double alpha : {10.0, 0.1}) {
    INFO("alpha = " << alpha);
    prox.set_alpha(alpha * prox.diagonal_scale());
    prox.set_centre(centre);
    const LocalProblemView& sub = prox.view();
    SparseNewton fresh;
    Vector r_reused = Vector::Zero(p.size()), r_fresh = r_reused, u(p.size());
    reused.compute(sub).solve(r_reused, u);
    fresh.compute(sub).solve(r_fresh, u);
    CHECK(reused.info().status == Status::Converged);
    CHECK(fresh.info().status == Status::Converged);
    const LocalProblem copy = make_local(3, DenseMatrix(SparseMatrix(sub.W)), Vector(sub.q), Vector(p.mu));
    CHECK(local_error(copy, r_reused) <= reused.settings().tol);
    CHECK((r_reused - r_fresh).norm() <= 1e-6 * (1 + r_fresh.norm()));
  }
}

TEST_CASE("ppa catalogue entries solve through the registry", "[ppa][catalogue]") {
  std::set<std::string> names, all;
  for (const auto& e : fcsolve_test::catalogue_entries())
    if (e.family == "ppa") {
      all.insert(e.name);
      if (e.solve_local) names.insert(e.name);
    }
  CHECK(all == std::set<std::string>{"ppa", "ppa-nsgs", "ppa-global"});
  CHECK(names == std::set<std::string>{"ppa", "ppa-nsgs"});
  const LocalProblem capsules = fclib::read_local(fcsolve_test::bundled("Capsules-i101-404.hdf5"));
  const LocalProblem p2 = random_problem(2, 20, 0.4, 3), p1 = random_problem(1, 20, 0.0, 4);
  for (const auto& name : names)
    for (const LocalProblem* p : {&capsules, &p2, &p1}) {
      INFO(name << ", d = " << p->d);
      const auto& e = fcsolve_test::catalogue_find(name);
      registry::SolveRequest req = registry::make_request(e);
      req.common.max_time = 20;
      req.settings.set_text("sigma", "2");
      const registry::SolveOutcome out = registry::solve(LocalProblemView(*p), e, req);
      CHECK(out.info.converged());
      CHECK(local_error(*p, out.r) <= 1e-8);
      registry::SolveRequest warm = req;
      warm.r0 = out.r;
      const registry::SolveOutcome again = registry::solve(LocalProblemView(*p), e, warm);
      CHECK(again.info.converged());
      CHECK(again.info.iterations <= 2);
    }
  const GlobalProblem g = fclib::read_global(fcsolve_test::bundled("GFC3D_Example1.hdf5"));
  const auto& e = fcsolve_test::catalogue_find("ppa");
  const registry::SolveOutcome out = registry::solve(GlobalProblemView(g), e, registry::make_request(e));
  CHECK(out.info.converged());  // FC/I by the registry's reduction
  registry::SolveRequest req = registry::make_request(e);
  CHECK_THROWS_AS(req.settings.set_text("sigma", "-1"), UsageError);
}

using fcsolve_test::independent_global_error;

TEST_CASE("ppa-global: the bundled and shared FC/I problems to 1e-8, and warm starts", "[ppa][global]") {
  const std::vector<std::string> files = fcsolve_test::bundled_and_shared_files("global");
  REQUIRE(files.size() >= 3);
  for (const auto& f : files) {
    INFO(f);
    const GlobalProblem g = fclib::read_global(f);
    REQUIRE(g.d == 3);
    REQUIRE_FALSE(g.has_bilateral());
    ProximalPointGlobal<Coulomb3D> ppa;
    ppa.settings().max_time = 60;  // a guard; the largest takes about a second
    ppa.compute(g);
    Vector r = Vector::Zero(g.size()), v(g.num_dofs());
    ppa.solve(r, v);
    CHECK(ppa.info().converged());
    const double e = independent_global_error(g, r, v);
    CHECK(e <= 1e-8);
    CHECK(ppa.info().error == Approx(e).epsilon(1e-8).margin(1e-300));
    // restarted from its own solution (v is recomputed from r)
    ppa.solve(r, v);
    CHECK(ppa.info().converged());
    CHECK(ppa.info().iterations <= 2);
    CHECK(independent_global_error(g, r, v) <= 1e-8);
  }
}

TEST_CASE("global Newton's contact compliance: 0 changes nothing, c > 0 solves FC/II(W + c I, q)",
          "[ppa][global][compliance]") {
  const GlobalProblem g = fclib::read_global(fcsolve_test::bundled("Box_Stacks-i0035-31-0.hdf5"));
  using GlobalNsn = GlobalNewton<AlartCurnierFunction, Coulomb3D>;
  const Index m = g.size(), n = g.num_dofs();
  GlobalNsn plain;
  plain.compute(g);
  Vector r0 = Vector::Zero(m), v0(n);
  plain.solve(r0, v0);
  REQUIRE(plain.info().converged());

  SECTION("a compliance set and reset to 0 gives the plain solve, bit for bit") {
    GlobalNsn toggled;
    toggled.compute(g);
    toggled.set_compliance(0.5 * toggled.lumped_diagonal_mean());
    Vector r = Vector::Zero(m), v(n);
    toggled.solve(r, v);
    toggled.set_compliance(0);
    r.setZero();
    toggled.solve(r, v);
    CHECK(toggled.info().iterations == plain.info().iterations);
    CHECK((r.array() == r0.array()).all());
    CHECK((v.array() == v0.array()).all());
    CHECK(toggled.free_velocity_norm() == plain.free_velocity_norm());
  }
  SECTION("c > 0 is the reduced problem with W + c I (problem/reduction.hpp, ProximalProblem)") {
    const double c = 0.3 * plain.lumped_diagonal_mean();
    REQUIRE(c > 0);
    GlobalNsn compliant;
    compliant.compute(g);
    compliant.set_compliance(c);
    Vector r = Vector::Zero(m), v(n);
    compliant.solve(r, v);
    REQUIRE(compliant.info().converged());
    const GlobalReduction<> reduction{GlobalProblemView(g)};
    ProximalProblem prox;
    prox.compute(reduction.local());
    prox.set_alpha(c);
    prox.set_centre(Vector::Zero(m));
    const LocalProblemView& sub = prox.view();
    const LocalProblem copy =
        make_local(3, DenseMatrix(SparseMatrix(sub.W)), Vector(sub.q), Vector(g.mu));
    CHECK(local_error(copy, r) <= 1e-7);
    CHECK((r - r0).norm() > 1e-6 * r0.norm());  // and it is another problem
  }
  SECTION("bad compliances are usage errors") {
    CHECK_THROWS_AS(plain.set_compliance(-1), UsageError);
    CHECK_THROWS_AS(plain.set_compliance(std::nan("")), UsageError);
    GlobalNsn fresh;
    CHECK_THROWS_AS(fresh.set_compliance(1), UsageError);
  }
}

TEST_CASE("ppa-global through the registry: native FC/I, global-only", "[ppa][global][catalogue]") {
  const auto& e = fcsolve_test::catalogue_find("ppa-global");
  CHECK(e.solves_global_natively());
  CHECK_FALSE(e.solve_local);
  const GlobalProblem g = fclib::read_global(fcsolve_test::bundled("GFC3D_Example1.hdf5"));
  registry::SolveRequest req = registry::make_request(e);
  const registry::SolveOutcome out = registry::solve(GlobalProblemView(g), e, req);
  CHECK(out.info.converged());
  CHECK(independent_global_error(g, out.r, out.v) <= 1e-8);
  CHECK(out.info.message.find("subproblems") != std::string::npos);  // solved natively
  // FC/II input is refused, as by the other global-only entries (nsn-ac-global)
  const LocalProblem p = fclib::read_local(fcsolve_test::bundled("Capsules-i101-404.hdf5"));
  CHECK_THROWS_AS(registry::solve(LocalProblemView(p), e, req), UsageError);
  CHECK_THROWS_AS(fcsolve_test::solve_named(LocalProblemView(p), "nsn-ac-global", req), UsageError);
}

TEST_CASE("ppa-global: typed errors, budgets and the best iterate", "[ppa][global][api]") {
  const GlobalProblem g = fclib::read_global(fcsolve_test::bundled("Box_Stacks-i0035-31-0.hdf5"));
  ProximalPointGlobal<Coulomb3D> ppa;
  Vector r = Vector::Zero(g.size()), v(g.num_dofs());
  CHECK_THROWS_AS(ppa.solve(r, v), UsageError);  // before compute()
  GlobalProblem bilateral = g;
  bilateral.G = SparseMatrix(g.num_dofs(), 1);
  bilateral.G.insert(0, 0) = 1;
  bilateral.G.makeCompressed();
  bilateral.b = Vector::Zero(1);
  CHECK_THROWS_AS(ppa.compute(bilateral), UsageError);
  ppa.compute(g);
  Vector short_v(g.num_dofs() - 1);
  CHECK_THROWS_AS(ppa.solve(r, short_v), InvalidProblem);
  r[0] = std::nan("");
  CHECK_THROWS_AS(ppa.solve(r, v), InvalidProblem);
  r.setZero();
  SECTION("an iteration budget returns the best iterate with its true error") {
    ppa.settings().max_iter = 1;
    ppa.solve(r, v);
    CHECK(ppa.info().status == Status::MaxIterations);
    CHECK(ppa.info().error == Approx(independent_global_error(g, r, v)).epsilon(1e-9));
  }
  SECTION("bad settings are usage errors") {
    ppa.settings().alpha_min = 0;
    CHECK_THROWS_AS(ppa.solve(r, v), UsageError);
  }
  SECTION("the callback sees each subproblem's full error and can stop the solve") {
    int calls = 0;
    ppa.settings().callback = [&](const IterationInfo& it) {
      ++calls;
      CHECK(it.full_error);
      return true;
    };
    ppa.solve(r, v);
    CHECK(calls == 1);
    CHECK(ppa.info().status == Status::Stopped);
  }
}
