// fcsolve::solve (include/fcsolve/solve.hpp) and the `auto` plan behind it:
// closed-form cases, local and global, where the exact r is known; a
// strongly coupled case that NSGS alone would take thousands of sweeps on,
// so that the plan must switch to Newton; determinism, warm starts, the
// iteration budget, and a bundled FCLIB problem. Success is judged by the
// distance to the closed form and by problem/error.hpp's error, never by the
// solver's own claim alone.
#include <fcsolve/problem/error.hpp>
#include <fcsolve/io/fclib.hpp>
#include <fcsolve/problem/reduced_density.hpp>
#include <fcsolve/scenes/elastic_stepper.hpp>
#include <fcsolve/solve.hpp>

#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <limits>
#include <string>
#include <thread>

using namespace fcsolve;

namespace {

SparseMatrix sparse(const DenseMatrix& A) {
  SparseMatrix S = A.sparseView();
  S.makeCompressed();
  return S;
}

LocalProblem local_problem(const DenseMatrix& W, const Vector& q, double mu) {
  LocalProblem p;
  p.d = 3;
  p.W = sparse(W);
  p.q = q;
  p.mu = Vector::Constant(q.size() / 3, mu);
  return p;
}

/// `pairs` pairs of contacts whose normals are coupled by [[1, c], [c, 1]],
/// tangents identity, mu = 0.5. With q_N = -(1 + c) both normals are
/// r_N = 1 (u_N = 0); the first contact of a pair sticks (q_T = (0.1, 0):
/// r_T = (-0.1, 0)), the second slides (q_T = (0, 2): r_T = (0, -0.5),
/// u_T = (0, 1.5)). Gauss-Seidel on the normals contracts by c^2 per sweep.
struct CoupledPairs {
  LocalProblem problem;
  Vector expected;
  CoupledPairs(int pairs, double c) {
    const Index m = 6 * pairs;
    DenseMatrix W = DenseMatrix::Identity(m, m);
    Vector q(m);
    expected.resize(m);
    for (int k = 0; k < pairs; ++k) {
      const Index a = 6 * k, b = a + 3;
      W(a, b) = W(b, a) = c;
      q.segment<6>(a) << -(1 + c), 0.1, 0, -(1 + c), 0, 2;
      expected.segment<6>(a) << 1, -0.1, 0, 1, 0, -0.5;
    }
    problem = local_problem(W, q, 0.5);
  }
};

bool ran(const Solution& s, const std::string& stage) {
  for (const auto& st : s.stages)
    if (st.name.rfind(stage, 0) == 0) return true;
  return false;
}

/// `auto` on p to tol, checked to converge by the independent error.
[[maybe_unused]] Solution solved_by_auto(const LocalProblem& p, double tol) {
  SolveSettings settings;
  settings.tol = tol;
  Solution s = fcsolve::solve(p, settings);
  INFO(s.info.message);
  CHECK(s.info.converged());
  CHECK(local_error(p, s.r) <= tol);
  return s;
}

}  // namespace

TEST_CASE("fcsolve::solve: one contact, closed forms, local and global", "[auto][closed-form]") {
  // W = I, mu = 0.5: take-off r = 0; sticking r = (1, -0.1, 0); sliding
  // r = (1, -0.5, 0) on the cone's boundary, opposite to u_T = (1.5, 0).
  struct Case {
    const char* name;
    Eigen::Vector3d q, r;
  };
  const Case cases[] = {{"take-off", {1, 0.3, 0}, {0, 0, 0}},
                        {"sticking", {-1, 0.1, 0}, {1, -0.1, 0}},
                        {"sliding", {-1, 2, 0}, {1, -0.5, 0}}};
  for (const Case& c : cases) {
    SECTION(c.name) {
      const LocalProblem p = local_problem(DenseMatrix::Identity(3, 3), c.q, 0.5);
      const Solution s = fcsolve::solve(p);
      CHECK(s.solver == "auto");
      CHECK(s.info.converged());
      CHECK((s.r - c.r).norm() <= 1e-10);
      CHECK(local_error(p, s.r) <= 1e-8);
      CHECK(s.info.error == Approx(local_error(p, s.r)).margin(1e-300));

      // FC/I with M = I, H = I, w = 0: v = r + f = u, the same contact.
      GlobalProblem g;
      g.M = sparse(DenseMatrix::Identity(3, 3));
      g.H = g.M;
      g.f = c.q;
      g.w = Vector::Zero(3);
      g.mu = Vector::Constant(1, 0.5);
      const Solution gs = fcsolve::solve(g);
      CHECK(gs.info.converged());
      CHECK((gs.r - c.r).norm() <= 1e-10);
      CHECK((gs.v - (c.r + c.q)).norm() <= 1e-10);
    }
  }
}

TEST_CASE("auto: with no solution and no time limit, the last sweeps stop on a plateau", "[auto]") {
  // Two contacts whose normals are coupled by [[1, -1], [-1, 1]], q_N = -1:
  // u_N1 + u_N2 = -2 whatever r, no solution. Every stage fails; the sweeps
  // that end the plan used to go on to max_iter (10^6).
  DenseMatrix W = DenseMatrix::Identity(6, 6);
  W(0, 3) = W(3, 0) = -1;
  Vector q = Vector::Zero(6);
  q[0] = q[3] = -1;
  const LocalProblem p = local_problem(W, q, 0.5);
  const Solution s = fcsolve::solve(p);
  INFO(s.info.message);
  CHECK_FALSE(s.info.converged());
  CHECK(s.info.status == Status::Stalled);
  CHECK(s.info.iterations < 200000);
  REQUIRE_FALSE(s.stages.empty());
  const auto& last = s.stages.back();
  CHECK(last.solver == "nsgs");
  CHECK(last.status == to_string(Status::Stalled));
  CHECK(last.why.find("the rest of the budget") != std::string::npos);
  CHECK(s.info.error == Approx(local_error(p, s.r)).epsilon(1e-10));
}

TEST_CASE("auto: strongly coupled contacts, closed form, Newton takes over", "[auto][closed-form]") {
  const CoupledPairs pairs(6, 0.999);  // 12 contacts: not left to NSGS alone
  SolveSettings settings;
  settings.tol = 1e-10;
  const Solution s = fcsolve::solve(pairs.problem, settings);
  INFO(s.info.message);
  CHECK(s.info.converged());
  CHECK(local_error(pairs.problem, s.r) <= 1e-10);
  CHECK((s.r - pairs.expected).norm() <= 1e-6 * pairs.expected.norm());
  CHECK(ran(s, "nsgs"));
  CHECK(ran(s, "newton"));  // sweeps contract by 0.998 only
  CHECK(s.info.message.find("stages [") != std::string::npos);
  int iterations = 0;
  for (const auto& st : s.stages) iterations += st.iterations;
  CHECK(iterations == s.info.iterations);
  // the result is the best iterate any stage reached
  double best = std::numeric_limits<double>::infinity();
  for (const auto& st : s.stages) best = std::min(best, st.error);
  CHECK(s.info.error == Approx(best).epsilon(1e-6).margin(1e-300));

  SECTION("deterministic") {
    const Solution again = fcsolve::solve(pairs.problem, settings);
    CHECK(again.r == s.r);
    CHECK(again.stages.size() == s.stages.size());
  }
  SECTION("a warm start at the solution runs no stage") {
    SolveSettings warm = settings;
    warm.r0 = s.r;
    const Solution w = fcsolve::solve(pairs.problem, warm);
    CHECK(w.info.converged());
    CHECK(w.stages.empty());
    CHECK(w.r == s.r);
  }
  SECTION("a tiny iteration budget: no false convergence, never worse than the start") {
    SolveSettings few = settings;
    few.max_iter = 3;
    const Solution f = fcsolve::solve(pairs.problem, few);
    CHECK_FALSE(f.info.converged());
    CHECK(f.info.iterations <= 3);
    const double start = local_error(pairs.problem, Vector::Zero(pairs.problem.size()));
    CHECK(local_error(pairs.problem, f.r) <= start);
    CHECK(f.info.error == Approx(local_error(pairs.problem, f.r)).margin(1e-300));
  }
  SECTION("another solver by name") {
    SolveSettings nsn = settings;
    nsn.solver = "nsn-ac";
    const Solution n = fcsolve::solve(pairs.problem, nsn);
    CHECK(n.solver == "nsn-ac");
    CHECK(n.stages.empty());
    CHECK(local_error(pairs.problem, n.r) <= 1e-10);
  }
}

TEST_CASE("auto: the interior-point stage stops when it crawls, not on its early plateau", "[auto]") {
  using namespace registry::auto_detail;
  const auto iterations_until_stop = [](const std::vector<double>& errors) {
    InteriorPointCrawl crawl;
    crawl.start();
    for (std::size_t k = 0; k < errors.size(); ++k)
      if (crawl.crawls(errors[k])) return int(k) + 1;
    return 0;
  };
  // path following done (1e-3 below the first iterate), then 0.05 % per
  // iteration: stops once 12 iterations gained less than 1 %
  std::vector<double> crawl = {1.0, 0.1, 1e-2, 1e-3};
  for (int k = 0; k < 30; ++k) crawl.push_back(crawl.back() * 0.9995);
  const int stop = iterations_until_stop(crawl);
  CHECK(stop == 4 + kCrawlWindow);
  // the same progress at the first iterate's level: the path following goes
  // on (a heavy-on-light stack's early plateau), no stop
  std::vector<double> plateau = {1.0};
  for (int k = 0; k < 30; ++k) plateau.push_back(plateau.back() * 0.9995);
  CHECK(iterations_until_stop(plateau) == 0);
  // the path lowers the error 40x, then it stays (a pile of 10^4 contacts,
  // held-out seed 720: 1.4 -> 3.6e-2 in 10 iterations, then 3.5e-2 for 90):
  // one decade below the first iterate is past the early plateau, stop
  std::vector<double> stuck = {1.4};
  for (int k = 0; k < 9; ++k) stuck.push_back(stuck.back() * 0.66);
  for (int k = 0; k < 30; ++k) stuck.push_back(stuck.back() * 0.9995);
  CHECK(stuck[9] <= kCrawlPathDone * stuck[0]);
  CHECK(iterations_until_stop(stuck) == 10 + kCrawlWindow);
  // 2 % per iteration below the first iterate's 1 %: progress, no stop
  std::vector<double> steady = {1.0, 1e-3};
  for (int k = 0; k < 30; ++k) steady.push_back(steady.back() * 0.98);
  CHECK(iterations_until_stop(steady) == 0);
  // errors that go up count as no progress; a non-finite one is the
  // engine's to handle and is not counted
  std::vector<double> bouncing = {1.0, 1e-3};
  for (int k = 0; k < 30; ++k) bouncing.push_back(k % 2 ? 2e-3 : std::numeric_limits<double>::quiet_NaN());
  CHECK(iterations_until_stop(bouncing) == 2 + 2 * kCrawlWindow);
  // start() forgets the previous run
  InteriorPointCrawl reused;
  for (double e : crawl) reused.crawls(e);
  CHECK(reused.fired());
  reused.start();
  CHECK_FALSE(reused.fired());
  CHECK_FALSE(reused.crawls(1e-9));
}

TEST_CASE("auto: the run's message is written whole when its first size guess is short", "[auto][report]") {
  using namespace registry::auto_detail;
  const std::string long_text(300, 'x');
  MessageWriter m(1);  // every piece makes it grow
  m("a", long_text, -1234567890123LL, 7, 0.000123, -4.56e-7, std::numeric_limits<double>::infinity());
  m(", ", std::string("end"));
  CHECK(std::move(m).take() == "a" + long_text + "-1234567890123" + "7" + "0.000123" + "-4.56e-07" + "null, end");

  Features f;
  f.nc = 2;
  f.mu_min = 0.1;
  f.mu_max = 0.5;
  registry::StageReport s;
  s.name = "nsgs";
  s.solver = "nsgs";
  s.seconds = 1.5e-6;
  s.iterations = 3;
  s.error = 2e-9;
  s.status = "converged";
  s.why = std::string(1000, 'w');  // far past the guess of 160 characters a stage
  const std::string message = run_message(f, {s, s}, "a note");
  const std::string stage = "{\"stage\": \"nsgs\", \"solver\": \"nsgs\", \"seconds\": 1.5e-06, \"iterations\": 3, "
                            "\"error\": 2e-09, \"status\": \"converged\", \"why\": \"" + s.why + "\"}";
  CHECK(message == "auto (nc=2 d=3 mu=[0.1,0.5]): stages [" + stage + ", " + stage + "]; a note");
}

TEST_CASE("auto: a factorising stage whose first step outlasts its budget is not started", "[auto]") {
  using namespace registry::auto_detail;
  FactorisationStepCost cost;
  const auto stage = [](int iterations, double solve_seconds) {
    SolverInfo info;
    info.iterations = iterations;
    info.solve_seconds = solve_seconds;
    return info;
  };
  // nothing measured: every stage may start
  CHECK_FALSE(cost.measured());
  CHECK(cost.fits(1e-6));
  cost.observe(stage(1, 20), 23);  // one step in 23 s, 3 s of it set-up (the 10^5 pile's Newton stage)
  CHECK(cost.seconds() == Approx(23));
  CHECK_FALSE(cost.fits(15));
  CHECK(cost.fits(30));
  CHECK(cost.fits(std::numeric_limits<double>::infinity()));  // no time limit
  cost.observe(stage(5, 10), 12);  // 5 steps in 10 s after 2 s of set-up: a first step costs 4 s
  CHECK(cost.seconds() == Approx(4));
  CHECK(cost.fits(5));
  CHECK_FALSE(cost.fits(3));
  cost.observe(stage(0, 0.5), 0.5);  // no iteration: nothing learnt about a step
  CHECK(cost.seconds() == Approx(4));
  cost.observe_first_step(-1);  // not timed
  CHECK(cost.seconds() == Approx(4));
  cost.observe_first_step(2.5);  // set-up to the end of a first iteration, timed
  CHECK(cost.seconds() == Approx(2.5));
}

TEST_CASE("auto: ADMM's first stage on FC/I ends at its share only for a Newton step that fits", "[auto]") {
  using namespace registry::auto_detail;
  AdmmHandover handover;
  // plan clock: the stage starts at 0, its share ends at 0.4, the run at 1
  handover.start(0, 0.4, 1.0);
  CHECK_FALSE(handover.hands_over(0.01));  // the first iteration: a first step of 0.01
  CHECK(handover.first_step() == Approx(0.01));
  CHECK_FALSE(handover.hands_over(0.39));
  CHECK(handover.hands_over(0.41));  // 0.01 fits the Newton share of what is left
  CHECK(handover.fired());

  handover.start(0, 0.4, 1.0);
  CHECK_FALSE(handover.hands_over(0.9));   // a first step of 0.9
  CHECK_FALSE(handover.hands_over(0.95));  // past the share, but 0.9 > 0.6 * 0.05: ADMM goes on
  CHECK_FALSE(handover.fired());
  // Nor at the deadline: ADMM's own max_time, its set-up counted, ends it.
  CHECK_FALSE(handover.hands_over(1.0));
  CHECK_FALSE(handover.fired());

  // no time limit: never
  handover.start(0, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
  CHECK_FALSE(handover.hands_over(0.01));
  CHECK_FALSE(handover.hands_over(1e9));
}

TEST_CASE("auto: a proximal stage cut by the clock while lowering the error keeps the time left", "[auto]") {
  using namespace registry::auto_detail;
  const auto stage = [](Status status, int iterations) {
    SolverInfo info;
    info.status = status;
    info.iterations = iterations;
    return info;
  };
  // 33 subproblems in 8.5 s, 1.7e-4 -> 1e-7, 5.7 s left (a pile of 3000)
  CHECK(proximal_keeps_time(stage(Status::TimeLimit, 33), 8.5, 1.7e-4, 1e-7, 5.7));
  // the same stage stopped by anything but the clock: the sweeps take the time
  for (const Status s : {Status::Stalled, Status::MaxIterations, Status::NumericalError})
    CHECK_FALSE(proximal_keeps_time(stage(s, 33), 8.5, 1.7e-4, 1e-7, 5.7));
  // cut by the clock without lowering the error
  CHECK_FALSE(proximal_keeps_time(stage(Status::TimeLimit, 33), 8.5, 1.7e-4, 1.7e-4, 5.7));
  // one subproblem of 0.38 s with 0.36 s left (the 10^4 pile on FC/I): does not fit
  CHECK_FALSE(proximal_keeps_time(stage(Status::TimeLimit, 1), 0.38, 4.3e-4, 2.7e-4, 0.36));
  CHECK(proximal_keeps_time(stage(Status::TimeLimit, 1), 0.38, 4.3e-4, 2.7e-4, 0.5));
  // no subproblem finished: its cost is the whole stage's
  CHECK_FALSE(proximal_keeps_time(stage(Status::TimeLimit, 0), 2.0, 1e-3, 9e-4, 1.5));
}

#ifdef FCSOLVE_WITH_KLU
TEST_CASE("auto: the sweeps' allowance follows what a Newton step costs on W's pattern", "[auto]") {
  using namespace registry::auto_detail;
  // 12 contacts coupled in pairs: J's LU fills nothing, a step costs its fixed part
  const CoupledPairs pairs(6, 0.5);
  const double sparse_step = newton_step_in_sweeps(pairs.problem);
  CHECK(sparse_step >= kNewtonStepFixedSweeps);
  CHECK(sparse_step <= kNewtonStepFixedSweeps + 5);
  // the same size, every two contacts coupled: the LU does about 2/3 m^3
  // flops on m^2 entries of W
  DenseMatrix W = DenseMatrix::Constant(36, 36, 0.01);
  W.diagonal().setConstant(1.0);
  const LocalProblem dense = local_problem(W, Vector::Constant(36, -1.0), 0.5);
  const double dense_step = newton_step_in_sweeps(dense);
  CHECK(dense_step >= sparse_step + 10);
  CHECK(dense_step <= kNewtonStepFixedSweeps + 36);
}

TEST_CASE("auto: sweeps that slow down hand over to Newton within the allowance", "[auto][fclib]") {
  using namespace registry::auto_detail;
  // Capsules: Gauss-Seidel's rate falls from 0.8 to 0.97 a sweep after the
  // warm start (docs/results.md, 2026-11-27), Newton converges in ~10 steps
  const fclib::Problem problem = fclib::read_problem(fcsolve_test::bundled("Capsules-i101-404.hdf5"));
  const auto& p = std::get<LocalProblem>(problem);
  const Solution s = solved_by_auto(p, 1e-8);
  INFO(s.info.message);
  REQUIRE(ran(s, "newton"));
  // the sweeps after the warm start (stages before the first Newton stage)
  int continued = 0;
  REQUIRE(s.stages.size() >= 2);
  CHECK(s.stages.front().name == "nsgs");
  for (std::size_t k = 1; k < s.stages.size() && s.stages[k].name == "nsgs"; ++k) continued += s.stages[k].iterations;
  CHECK(continued <= kNewtonStepsWorthSweeping * newton_step_in_sweeps(p));
}

TEST_CASE("auto: sweeps that spend the allowance just short of tol finish with a last chunk",
          "[auto][fclib]") {
  using namespace registry::auto_detail;
  if (!fcsolve_test::have_shared_data()) {
    WARN("no shared FCLIB collection at " << fcsolve_test::shared_data_dir()
                                          << ": LMGC_100_PR_PerioBox is not bundled, case skipped");
    return;
  }
  // PerioBox at 1e-4: the allowance (three Newton steps, about 225 sweeps)
  // runs out some 15 sweeps short of tol, a fraction of one step
  const fclib::Problem problem = fclib::read_problem(fcsolve_test::shared_data_dir() +
                                                     "/local/LMGC_100_PR_PerioBox-i00361-60-03000.hdf5");
  const auto& p = std::get<LocalProblem>(problem);
  const Solution s = solved_by_auto(p, 1e-4);
  INFO(s.info.message);
  CHECK_FALSE(ran(s, "newton"));
  REQUIRE(!s.stages.empty());
  const auto& final_stage = s.stages.back();
  CHECK(final_stage.name == "nsgs");
  CHECK(final_stage.why.find("last chunk") != std::string::npos);
  CHECK(final_stage.iterations <= std::ceil(newton_step_in_sweeps(p)));
}
#endif

TEST_CASE("auto: a bundled FCLIB problem of each kind", "[auto][fclib]") {
  for (const char* name : {"OneObject-i1028-138.hdf5", "Capsules-i101-404.hdf5",
                           "Box_Stacks-i0035-31-0.hdf5"}) {
    const std::string path = fcsolve_test::bundled(name);
    const fclib::Problem problem = fclib::read_problem(path);
    INFO(name);
    if (const auto* lp = std::get_if<LocalProblem>(&problem)) {
      const Solution s = fcsolve::solve(*lp);
      INFO(s.info.message);
      CHECK(s.info.converged());
      CHECK(local_error(*lp, s.r) <= 1e-8);
    } else {
      const auto& gp = std::get<GlobalProblem>(problem);
      // Rigid bodies: M^-1 acts within each body's block, which H fills.
      CHECK(inverse_mass_times_h_nonzeros(gp) == double(gp.H.nonZeros()));
      const Solution s = fcsolve::solve(gp);
      INFO(s.info.message);
      CHECK(s.info.converged());
      CHECK_FALSE(ran(s, "newton-global"));  // reduced: W is sparse
      GlobalReduction<DefaultBackend> reduction(gp, /*form_W=*/false);
      CHECK(global_error_report(gp, reduction.free_velocity_norm(), s.r, s.v, s.lambda).error <= 1e-8);
    }
  }
}

/// An elastic block of hexahedra pressed on a plane (scenes/), stepped in
/// time until ~100 bottom nodes touch: one elastic body, so M^-1 couples
/// every dof and the reduced W would be dense.
static GlobalProblem elastic_block_on_plane() {
  scenes::HexBlock block;
  block.size = scenes::Vec3(0.4, 0.4, 0.2);
  block.nx = block.ny = 11;
  block.nz = 1;
  block.origin = scenes::Vec3(0, 0, 2e-5);
  scenes::ElasticLoad load;
  load.h = 1e-3;
  load.ramp_time = 4e-3;
  scenes::ElasticScene scene({block}, load);
  scenes::StepSettings settings;
  settings.h = 1e-3;
  settings.tol = 1e-6;
  settings.max_iter = 20;
  scenes::ElasticStepper stepper(scene, settings);
  for (int k = 0; k < 8 && stepper.contacts().size() < 100; ++k) stepper.step();
  return stepper.global();
}

TEST_CASE("auto: FC/I of an elastic block is solved in (v, r), W never formed", "[auto][fem]") {
  const GlobalProblem p = elastic_block_on_plane();
  REQUIRE(p.mu.size() >= 100);

  // One component: every column of H touches all n dofs.
  CHECK(inverse_mass_times_h_nonzeros(p) == double(p.f.size()) * double(p.w.size()));

  const Solution s = fcsolve::solve(p);
  INFO(s.info.message);
  CHECK(ran(s, "admm-global"));  // FC/I natively: ADMM first, Newton if it needs to
  CHECK_FALSE(ran(s, "nsgs"));  // never reduced (the reduced plan starts with sweeps)
  CHECK(s.info.converged());
  GlobalReduction<DefaultBackend> reduction(p, /*form_W=*/false);
  CHECK(global_error_report(p, reduction.free_velocity_norm(), s.r, s.v, s.lambda).error <= 1e-8);
  // Deterministic: the same call gives the same iterate.
  CHECK(fcsolve::solve(p).r == s.r);
}

TEST_CASE("auto: FC/I natively, ADMM hands over to Newton only where a Newton step fits", "[auto][fem]") {
  const GlobalProblem p = elastic_block_on_plane();
  REQUIRE(p.mu.size() >= 100);
  // The clock is moved on by the caller's callback, which waits at one
  // iteration until a fraction of max_time has passed (a stand-in for a
  // slow factorisation or a loaded machine). ADMM's first step bounds a
  // Newton step from below.
  constexpr double kMaxTime = 3.0;
  SolveSettings settings;
  settings.max_time = kMaxTime;
  Stopwatch clock;  // started before the run's: it reads at least as much
  const auto wait_at = [&clock](int iteration, double fraction) {
    return [&clock, iteration, fraction](const IterationInfo& it) {
      const double wait = fraction * kMaxTime - clock.seconds();
      if (it.iteration == iteration && wait > 0) std::this_thread::sleep_for(std::chrono::duration<double>(wait));
      return false;
    };
  };
  GlobalReduction<DefaultBackend> reduction(p, /*form_W=*/false);
  const auto independent_error = [&](const Solution& s) {
    return global_error_report(p, reduction.free_velocity_norm(), s.r, s.v, s.lambda).error;
  };

  SECTION("a first step of 85 % of max_time: ADMM keeps the time, no Newton stage starts") {
    settings.tol = 1e-18;  // below round-off: ADMM ends at its 200 iterations with ~15 % left
    settings.callback = wait_at(1, 0.85);
    const Solution s = fcsolve::solve(p, settings);
    INFO(s.info.message);
    REQUIRE(s.stages.size() == 3);
    CHECK(s.stages[0].solver == "admm-global");
    CHECK(s.stages[0].iterations == 200);  // not handed over at its 40 %
    CHECK(s.stages[1].solver == "nsn-ac-global");
    CHECK(s.stages[1].status == "not-run");
    CHECK(s.stages[2].solver == "admm-global");
    CHECK(s.stages[2].status == "not-run");
    CHECK(s.info.status == Status::TimeLimit);
    CHECK(independent_error(s) == Approx(s.info.error).epsilon(1e-12));
  }
  SECTION("a quick first step: ADMM hands over at its share, Newton finishes") {
    settings.callback = wait_at(2, 0.45);  // past ADMM's 40 % at its second iteration
    const Solution s = fcsolve::solve(p, settings);
    INFO(s.info.message);
    REQUIRE(s.stages.size() >= 2);
    CHECK(s.stages[0].solver == "admm-global");
    CHECK(s.stages[0].iterations == 2);
    CHECK(s.stages[0].status == "timeout");
    // ended by the handover (ADMM's own max_time is the run's, not its share)
    CHECK(s.stages[0].why.find("ended at its share of the time") != std::string::npos);
    CHECK(s.stages[1].solver == "nsn-ac-global");
    CHECK(s.info.converged());
    CHECK(independent_error(s) <= settings.tol);
  }
}
