// The solver contract, checked for every catalogue entry (issue 15): on the
// bundled problems and on small cases of every kind it applies to (3D, 2D,
// frictionless, one contact, mu = 0, bilateral constraints with b = 0 and
// b != 0), each entry
//   - returns r, u (and v, lambda) of the problem's sizes;
//   - reports an honest status: "converged" only when the error recomputed
//     here is within tol, and the registry's own re-check never has to
//     downgrade a claim;
//   - restarted from its own solution, converges again in at most 2 iterations;
//   - rejects a NaN in the warm start with a clear error;
//   - honours max_time (0 and a tiny budget): it returns, sizes and status honest;
//   - gives bit-identical results on two identical runs.
// An entry that does not apply to a kind of problem says so with a UsageError.
#include "test_support.hpp"

#include <fcsolve/problem/error.hpp>
#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/io/fclib.hpp>
#include <fcsolve/problem/reduction.hpp>
#include <fcsolve/newton.hpp>
#include <fcsolve/nipm.hpp>
#include <fcsolve/nsgs.hpp>
#include <fcsolve/ppa.hpp>
#include <fcsolve/vi.hpp>
#include "test_catalogue.hpp"

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <thread>
#include <variant>
#include <vector>

using namespace fcsolve;

// The solver contract (docs/architecture.md), at compile time, for one
// instantiation of every solver class; the catalogue's entries assert it
// for every instantiation they use.
static_assert(satisfies_solver_contract_v<
              Nsgs<Coulomb3D, DenseStorage<3>, local::Enumerative<Coulomb3D>>, LocalProblemView>);
static_assert(satisfies_solver_contract_v<
              Nsgs<Coulomb2D, BlockSparseStorage<2>, local::Hybrid<Coulomb2D>>, LocalProblemView>);
static_assert(satisfies_solver_contract_v<Newton<AlartCurnierFunction, Coulomb3D, SparseStorage<3>>,
                                          LocalProblemView>);
static_assert(satisfies_solver_contract_v<GlobalNewton<NaturalMapFunction, Coulomb2D>,
                                          GlobalProblemView>);
static_assert(satisfies_solver_contract_v<ProjectedFixedPoint<Coulomb3D, SparseStorage<3>>,
                                          LocalProblemView>);
static_assert(satisfies_solver_contract_v<ProximalPoint<Coulomb3D>, LocalProblemView>);
static_assert(satisfies_solver_contract_v<
              ProximalPoint<Coulomb2D, Nsgs<Coulomb2D, BlockSparseStorage<2>>>, LocalProblemView>);
// Not a solver: the contract is not vacuous.
static_assert(!satisfies_solver_contract_v<LocalProblem, LocalProblemView>);
static_assert(!satisfies_solver_contract_v<Newton<AlartCurnierFunction, Coulomb3D, SparseStorage<3>>,
                                           GlobalProblemView>);
static_assert(satisfies_solver_contract_v<ipm::LocalSocqpIpm<Coulomb3D>, LocalProblemView>);
static_assert(satisfies_solver_contract_v<ipm::LocalAclm<Coulomb2D>, LocalProblemView>);
static_assert(satisfies_solver_contract_v<ipm::GlobalNipm<Coulomb3D>, GlobalProblemView>);
static_assert(!satisfies_solver_contract_v<ipm::GlobalNipm<Coulomb3D>, LocalProblemView>);

namespace {

using AnyProblem = std::variant<LocalProblem, GlobalProblem>;

struct Case {
  std::string name;
  AnyProblem problem;
};

/// A well-conditioned symmetric positive definite W of size m.
DenseMatrix spd(Index m, unsigned seed) {
  std::srand(seed);
  const DenseMatrix A = DenseMatrix::Random(m, m);
  return A * A.transpose() / double(m) + DenseMatrix::Identity(m, m);
}

LocalProblem local_case(int d, Index nc, double mu, unsigned seed) {
  LocalProblem p;
  p.d = d;
  const Index m = d * nc;
  p.W = spd(m, seed).sparseView();
  p.W.makeCompressed();
  std::srand(seed + 1);
  p.q = Vector::Random(m);
  for (Index a = 0; a < nc; ++a) p.q[a * d] = -std::abs(p.q[a * d]) - 0.1;  // pressing contacts
  p.mu = Vector::Constant(nc, mu);
  return p;
}

/// A one-body, two-contact global problem with one bilateral constraint.
GlobalProblem bilateral_case(double b) {
  GlobalProblem g;
  g.d = 3;
  const Index n = 6, m = 6;
  g.M = spd(n, 7).sparseView();
  DenseMatrix H = DenseMatrix::Identity(n, m);
  H(3, 1) = 0.2;
  g.H = H.sparseView();
  DenseMatrix G = DenseMatrix::Zero(n, 1);
  G(1, 0) = 1;
  G(4, 0) = -1;
  g.G = G.sparseView();
  g.f = Vector::Zero(n);
  g.f << -1, 0.3, -0.2, -2, 0.1, 0.4;
  g.w = Vector::Zero(m);
  g.b = Vector::Constant(1, b);
  g.mu = Vector::Constant(2, 0.4);
  for (auto* A : {&g.M, &g.H, &g.G}) A->makeCompressed();
  return g;
}

/// An elastic body (M^-1 dense: one 30-dof block, above
/// kMaxDenseInverseBlock) with nc contacts: by default 70, whose 210
/// columns of W span two of the reduction's blocks of columns.
GlobalProblem elastic_case(Index nc = 70) {
  GlobalProblem g;
  g.d = 3;
  const Index n = 30, m = 3 * nc;
  g.M = spd(n, 21).sparseView();
  std::srand(22);
  DenseMatrix H = DenseMatrix::Zero(n, m);
  for (Index j = 0; j < m; ++j)
    for (Index k = 0; k < 3; ++k) H((j * 7 + k * 11) % n, j) = 1 + 0.5 * double(std::rand() % 100) / 100;
  g.H = H.sparseView();
  g.f = -Vector::Ones(n);
  g.w = Vector::Zero(m);
  g.mu = Vector::Constant(nc, 0.3);
  for (auto* A : {&g.M, &g.H}) A->makeCompressed();
  return g;
}

/// elastic_case() with one bilateral constraint: W comes from the
/// saddle-point matrix K, by blocks of columns under a time limit too.
GlobalProblem elastic_bilateral_case() {
  GlobalProblem g = elastic_case();
  DenseMatrix G = DenseMatrix::Zero(g.M.rows(), 1);
  G(1, 0) = 1;
  G(4, 0) = -1;
  g.G = G.sparseView();
  g.G.makeCompressed();
  g.b = Vector::Constant(1, 0.1);
  return g;
}

/// Entry `name` on g (an elastic body) asked for 1e-9 s: forming W outlasts
/// it, so the run returns its start (r = 0), timeout, no iteration, and the
/// error of that start as computed here independently; given 10 s the same
/// entry iterates and lowers that error.
registry::SolveOutcome check_start_returned_when_W_outlasts(const GlobalProblem& g, const std::string& name) {
  registry::SolveRequest req = registry::make_request(fcsolve_test::catalogue_find(name));
  req.common.max_time = 1e-9;
  const registry::SolveOutcome out = fcsolve_test::solve_named(GlobalProblemView(g), name, req);
  CHECK(out.info.status == Status::TimeLimit);
  CHECK(out.info.iterations == 0);
  CHECK(out.r.isZero(0));
  CHECK(out.info.message.find("forming W") != std::string::npos);
  CHECK(out.info.error == Approx(fcsolve_test::independent_global_error(g, out.r, out.v, out.lambda)).epsilon(1e-8));
  req.common.max_time = 10;
  const registry::SolveOutcome solved = fcsolve_test::solve_named(GlobalProblemView(g), name, req);
  CHECK(solved.info.iterations > 0);
  CHECK(solved.info.error < out.info.error);
  return out;
}

std::vector<Case> contract_cases() {
  std::vector<Case> cases;
  cases.push_back({"Rover1039 (3D)", fclib::read_local(fcsolve_test::bundled("Rover1039.hdf5"))});
  cases.push_back({"FC3D_Example1 (3D)", fclib::read_local(fcsolve_test::bundled("FC3D_Example1.hdf5"))});
  cases.push_back({"GFC3D_Example1 (FC/I)", fclib::read_global(fcsolve_test::bundled("GFC3D_Example1.hdf5"))});
  cases.push_back({"3D, one contact", local_case(3, 1, 0.3, 11)});
  cases.push_back({"3D, mu = 0", local_case(3, 4, 0.0, 12)});
  cases.push_back({"2D", local_case(2, 5, 0.5, 13)});
  cases.push_back({"frictionless", local_case(1, 6, 0.0, 14)});
  cases.push_back({"FC/I, G with b = 0", bilateral_case(0.0)});
  cases.push_back({"FC/I, G with b != 0", bilateral_case(0.3)});
  return cases;
}

registry::SolveOutcome run(const AnyProblem& problem, const registry::SolverEntry& e,
                           const registry::SolveRequest& req) {
  return std::visit(
      [&](const auto& p) {
        using T = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<T, LocalProblem>) return registry::solve(LocalProblemView(p), e, req);
        else return registry::solve(GlobalProblemView(p), e, req);
      },
      problem);
}

/// The error of what a solve returned, recomputed here from the problem.
double recomputed_error(const AnyProblem& problem, const registry::SolveOutcome& out) {
  if (const auto* lp = std::get_if<LocalProblem>(&problem)) return local_error(*lp, out.r);
  return fcsolve_test::independent_global_error(std::get<GlobalProblem>(problem), out.r, out.v, out.lambda);
}

void check_sizes(const AnyProblem& problem, const registry::SolveOutcome& out) {
  std::visit(
      [&](const auto& p) {
        CHECK(out.r.size() == p.size());
        CHECK(out.u.size() == p.size());
        using T = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<T, GlobalProblem>) {
          CHECK(out.v.size() == p.num_dofs());
          CHECK(out.lambda.size() == (p.has_bilateral() ? p.G.cols() : 0));
        }
      },
      problem);
}

void check_honest(const AnyProblem& problem, const registry::SolveOutcome& out, double tol) {
  INFO("status " << to_string(out.info.status) << ", message: " << out.info.message);
  CHECK(out.info.status != Status::NotRun);
  CHECK(out.info.message.find("claimed convergence") == std::string::npos);
  if (!out.r.allFinite()) return;  // a numerical failure may return non-finite r
  const double e = recomputed_error(problem, out);
  if (out.info.converged()) CHECK(e <= tol);
  if (std::isfinite(e)) CHECK(out.info.error == Approx(e).epsilon(1e-8).margin(1e-300));
}

}  // namespace

TEST_CASE("every catalogue entry honours the solver contract", "[contract][catalogue]") {
  const std::vector<Case> cases = contract_cases();
  const double tol = 1e-8;
  int applicable = 0;
  for (const auto& e : fcsolve_test::catalogue_entries()) {
    for (const auto& c : cases) {
      INFO("solver " << e.name << " on " << c.name);
      registry::SolveRequest req = registry::make_request(e);
      req.common.tol = tol;
      req.common.max_time = 20;
      registry::SolveOutcome first;
      try {
        first = run(c.problem, e, req);
      } catch (const UsageError& u) {
        // does not apply: it must say so clearly
        CHECK(std::string(u.what()).size() > 10);
        continue;
      }
      ++applicable;
      check_sizes(c.problem, first);
      check_honest(c.problem, first, tol);

      // deterministic: a second identical run is bit-identical
      const registry::SolveOutcome second = run(c.problem, e, req);
      CHECK(second.info.status == first.info.status);
      CHECK(second.info.iterations == first.info.iterations);
      CHECK(second.r.size() == first.r.size());
      if (second.r.size() == first.r.size()) CHECK((second.r.array() == first.r.array()).all());

      // restarted from its own solution, it converges at once
      if (first.info.converged()) {
        registry::SolveRequest warm = req;
        warm.r0 = first.r;
        warm.v0 = first.v;
        const registry::SolveOutcome again = run(c.problem, e, warm);
        check_honest(c.problem, again, tol);
        CHECK(again.info.converged());
        CHECK(again.info.iterations <= 2);
      }

      // a NaN in the warm start is refused with an error naming it
      registry::SolveRequest nan = req;
      nan.r0 = Vector::Zero(first.r.size());
      nan.r0[0] = std::numeric_limits<double>::quiet_NaN();
      CHECK_THROWS_AS(run(c.problem, e, nan), InvalidProblem);

      // a time budget of 0 is refused (the registry checks every request);
      // tiny ones: it returns, sizes and status honest
      registry::SolveRequest none = req;
      none.common.max_time = 0;
      CHECK_THROWS_AS(run(c.problem, e, none), UsageError);
      for (double budget : {1e-9, 1e-5}) {
        INFO("max_time " << budget);
        registry::SolveRequest timed = req;
        timed.common.max_time = budget;
        timed.common.tol = 1e-13;  // out of reach in so little time, bar exact solutions
        const registry::SolveOutcome out = run(c.problem, e, timed);
        check_sizes(c.problem, out);
        check_honest(c.problem, out, timed.common.tol);
      }
    }
  }
  CHECK(applicable >= int(fcsolve_test::catalogue_entries().size()));  // each applies somewhere
}

TEST_CASE("every settings enum parses what its to_string writes, and nothing else",
          "[contract][registry]") {
  auto round_trip = [](auto values) {
    using E = typename decltype(values)::value_type;
    for (const E e : values) CHECK(parse_enum<E>(enum_to_string(e), "setting") == e);
    CHECK_THROWS_AS(parse_enum<E>("no-such-value", "setting"), UsageError);
    CHECK(enum_choices<E>().size() == values.size());
  };
  round_trip(std::vector<LineSearch>{LineSearch::None, LineSearch::Armijo, LineSearch::GoldsteinPrice});
  round_trip(std::vector<RhoStrategy>{RhoStrategy::Constant, RhoStrategy::SpectralNorm,
                                      RhoStrategy::SplitSpectralNorm, RhoStrategy::Adaptive});
  round_trip(std::vector<ContactOrdering>{ContactOrdering::Natural, ContactOrdering::ShuffledOnce,
                                          ContactOrdering::ShuffledEachSweep,
                                          ContactOrdering::Coloured, ContactOrdering::LoadAscending});
  round_trip(std::vector<StepRule>{StepRule::SelfAdaptive, StepRule::Fixed});
  round_trip(std::vector<EgSecondStep>{EgSecondStep::Predictor, EgSecondStep::Korpelevich});
  // the catalogue offers exactly the enum's names, its default among them
  const registry::SolverEntry& e = fcsolve_test::catalogue_find("nsn-ac");
  registry::SolveRequest req = registry::make_request(e);
  CHECK(req.settings.enumerated<LineSearch>("line_search") == NewtonSettings().line_search);
  CHECK(req.settings.enumerated<RhoStrategy>("rho_strategy") == NewtonSettings().rho_strategy);
  req.settings.set_text("line_search", "armijo");
  CHECK(req.settings.enumerated<LineSearch>("line_search") == LineSearch::Armijo);
}

TEST_CASE("settings copied from an entry's cached defaults are independent once set",
          "[contract][registry]") {
  const registry::SolverEntry& e = fcsolve_test::catalogue_find("nsn-ac");
  const registry::SettingValues& defaults = fcsolve_test::catalogue_default_settings(e);
  CHECK(&defaults == &fcsolve_test::catalogue_default_settings(e));  // built once
  const long long window = defaults.integer("stall_window");
  const registry::SettingValues a = defaults;  // shares one map (copy on write)
  registry::SettingValues b = a;
  b.set("stall_window", window + 7);
  b.set_text("line_search", "armijo");
  CHECK(b.integer("stall_window") == window + 7);
  CHECK(b.enumerated<LineSearch>("line_search") == LineSearch::Armijo);
  for (const registry::SettingValues* v : {&defaults, &a}) {
    CHECK(v->integer("stall_window") == window);
    CHECK(v->enumerated<LineSearch>("line_search") == NewtonSettings().line_search);
    CHECK(v->values().size() == e.settings.size());
  }
  CHECK(registry::make_request(e).settings.values() == defaults.values());
  CHECK(registry::SettingValues().values().empty());
  CHECK_THROWS_AS(registry::SettingValues().integer("stall_window"), UsageError);
}

namespace {

/// Just enough of a solver for registry::compute_within_time: settings and a
/// compute() that takes at least 20 ms (it sleeps).
struct SlowSetUpSolver {
  SolverSettings s;
  int computed = 0;
  SolverSettings& settings() { return s; }
  SlowSetUpSolver& compute(const LocalProblemView&) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ++computed;
    return *this;
  }
};

}  // namespace

TEST_CASE("max_time counts the set-up: compute() and a reduction to FC/II are charged to it",
          "[contract][catalogue]") {
  const LocalProblem p = local_case(3, 1, 0.3, 11);
  SECTION("compute(): what it took is taken off the solver's max_time") {
    SlowSetUpSolver solver;
    solver.s.max_time = 10;
    registry::compute_within_time(solver, LocalProblemView(p));
    CHECK(solver.computed == 1);
    CHECK(solver.s.max_time <= 10 - 0.02);
    CHECK(solver.s.max_time > 0);
  }
  SECTION("a set-up longer than max_time leaves a sliver, still a valid limit") {
    SlowSetUpSolver solver;
    solver.s.max_time = 0.01;
    registry::compute_within_time(solver, LocalProblemView(p));
    CHECK(solver.s.max_time > 0);
    CHECK(solver.s.max_time < 1e-6);
  }
  SECTION("no limit stays no limit") {
    SlowSetUpSolver solver;
    registry::compute_within_time(solver, LocalProblemView(p));
    CHECK(solver.computed == 1);
    CHECK(std::isinf(solver.s.max_time));
  }
  SECTION("an FC/II entry run on FC/I is given what the reduction left") {
    const GlobalProblem g = fclib::read_global(fcsolve_test::bundled("GFC3D_Example1.hdf5"));
    registry::SolverEntry probe("probe", "test", "records the max_time it is given");
    double given = -1;
    probe.solve_local = [&given](const LocalProblemView& reduced, const registry::SolveRequest& req) {
      given = req.common.max_time;
      registry::SolveOutcome out;
      out.r = Vector::Zero(reduced.size());
      out.info.status = Status::MaxIterations;
      return out;
    };
    registry::SolveRequest req = registry::make_request(probe);
    req.common.max_time = 10;
    const registry::SolveOutcome out = registry::solve(GlobalProblemView(g), probe, req);
    CHECK(out.info.status == Status::MaxIterations);
    CHECK(given < 10);
    CHECK(given > 9);
    req.common.max_time = std::numeric_limits<double>::infinity();
    registry::solve(GlobalProblemView(g), probe, req);
    CHECK(std::isinf(given));
  }
  SECTION("an elastic body's W is formed by blocks within a limit, and given up once it is spent") {
    for (const GlobalProblem& g : {elastic_case(), elastic_bilateral_case()}) {  // M^-1; K^-1 (with G)
      const GlobalReduction<> no_limit(g), by_blocks(g, /*form_W=*/true, 1e9), given_up(g, true, 1e-12);
      REQUIRE(no_limit.formed_W());
      REQUIRE(by_blocks.formed_W());
      // W = H^T (K^-1 [H; 0])_v densely, K = [M -G; G^T 0] (problem/reduction.hpp)
      const Index n = g.M.rows(), k = g.G.cols();
      DenseMatrix K = DenseMatrix::Zero(n + k, n + k), B = DenseMatrix::Zero(n + k, g.H.cols());
      K.topLeftCorner(n, n) = DenseMatrix(g.M);
      K.topRightCorner(n, k) = -DenseMatrix(g.G);
      K.bottomLeftCorner(k, n) = DenseMatrix(g.G).transpose();
      B.topRows(n) = DenseMatrix(g.H);
      const DenseMatrix W = DenseMatrix(g.H.transpose()) * DenseMatrix(K.lu().solve(B).topRows(n));
      CHECK((DenseMatrix(no_limit.local().W) - W).norm() <= 1e-12 * W.norm());
      CHECK((no_limit.local().W - by_blocks.local().W).norm() <= 1e-13 * no_limit.local().W.norm());
      CHECK(!given_up.formed_W());
      CHECK(given_up.local().W.size() == 0);
      CHECK((given_up.local().q - no_limit.local().q).norm() <= 1e-13 * no_limit.local().q.norm());
      const Vector r = Vector::Constant(g.H.cols(), 0.1);
      CHECK((given_up.velocity(r) - no_limit.velocity(r)).norm() <= 1e-13 * no_limit.velocity(r).norm());
      if (g.has_bilateral())
        CHECK((given_up.multipliers(r) - no_limit.multipliers(r)).norm() <= 1e-12 * no_limit.multipliers(r).norm());
    }
  }
  SECTION("a W completed past the limit is kept (one block of columns, a limit of 1e-12 s)") {
    const GlobalProblem g = elastic_case(/*nc=*/10);  // 30 columns: the first block is the last
    const GlobalReduction<> no_limit(g), late(g, /*form_W=*/true, 1e-12);
    REQUIRE(late.formed_W());
    CHECK((no_limit.local().W - late.local().W).norm() == 0);
  }
  SECTION("an FC/II entry on FC/I whose reduction outlasts max_time returns its start, no iteration") {
    const GlobalProblem g = elastic_case();
    const registry::SolveOutcome out = check_start_returned_when_W_outlasts(g, "nsgs");
    CHECK((g.M * out.v - g.f).norm() <= 1e-12 * g.f.norm());  // v balances the start r = 0
  }
  SECTION("a native FC/I entry that reduces bilateral constraints itself gives what the reduction left") {
    const GlobalProblem g = bilateral_case(0.3);
    registry::SolveRequest req;
    req.common.max_time = 10;
    double given = -1;
    const auto probe = [&given](const LocalProblemView& reduced, const registry::SolveRequest& within) {
      given = within.common.max_time;
      registry::SolveOutcome out;
      out.r = Vector::Zero(reduced.size());
      return out;
    };
    const registry::SolveOutcome out = registry::solve_bilateral_by_reduction(GlobalProblemView(g), req, probe);
    CHECK(out.lambda.size() == 1);  // reduced, and the multiplier recovered
    CHECK(given < 10);
    CHECK(given > 9);
    req.common.max_time = std::numeric_limits<double>::infinity();
    registry::solve_bilateral_by_reduction(GlobalProblemView(g), req, probe);
    CHECK(std::isinf(given));
  }
  SECTION("... and returns its start when forming W outlasts max_time") {
    const registry::SolveOutcome out = check_start_returned_when_W_outlasts(elastic_bilateral_case(), "nsn-ac-global");
    CHECK(out.lambda.size() == 1);
  }
}
