// The semismooth Newton family: time to 1e-8 from r = 0 (compute() and
// solve(): what a user pays per problem) for the four formulations, the
// hybrid, the two sparse LU policies, and the reduced against the global
// form on FC/I problems (reduction included for the reduced form).
// Counters: Newton iterations (and fallback sweeps), the share of the time
// spent in factorisations and solves of the Newton systems, the final error.
//   ./build/bench/bench_newton --benchmark_min_time=0.01
//   FCSOLVE_BENCH_DATA=DIR ./build/bench/bench_newton   (problems of the same names elsewhere)
// Compare ratios within one run (the machine is shared and noisy).
#include "bench_support.hpp"

#include <fcsolve/linalg/eigen_backend.hpp>
#include <fcsolve/linalg/suitesparse_backend.hpp>
#include <fcsolve/newton.hpp>
#include <fcsolve/problem/reduction.hpp>

namespace {

using namespace fcsolve;
using fcsolve_bench::global_problem;
using fcsolve_bench::local_problem;

// Rigid multibody (rank-deficient W): 4, 52 and 225 contacts; FEM (full rank): 54.
const char* const kRover = "Rover1039";
const char* const kBoxes = "BoxesStack1-i100000-32";
const char* const kCapsules = "Capsules-i101-404";
const char* const kConfeti = "Confeti-ex03-Fc3D-SBM";
// Global problems: rigid boxes (n = 450), FEM (LMGC, n = 162).
const char* const kBoxStacks = "Box_Stacks-i0035-31-0";
const char* const kLmgc = "LMGC_GlobalFrictionContactProblem00046";

void report(benchmark::State& state, const SolverInfo& info, const NewtonCounters& c) {
  const double total = info.setup_seconds + info.solve_seconds;
  state.counters["iterations"] = info.iterations;
  state.counters["newton_steps"] = c.steps;
  state.counters["sweeps"] = c.sweeps;
  state.counters["factorisation_share"] = total > 0 ? c.factorisation_seconds / total : 0;
  state.counters["error"] = info.error;
  if (!info.converged()) state.SkipWithError(to_string(info.status));
}

/// Newton on FC/II from r = 0: compute() + solve().
template <template <class> class F, class Storage = SparseStorage<3>,
          class Linear = DefaultNewtonLinearSolver<Storage>>
void BM_Newton(benchmark::State& state, const char* name, bool hybrid) {
  const LocalProblem& p = local_problem(name);
  NewtonSettings s;
  s.hybrid = hybrid;
  if (hybrid) s.stall_window = 20;
  Vector r(p.size()), u(p.size());
  Newton<F, Coulomb3D, Storage, Linear> nsn(s);
  for (auto _ : state) {
    r.setZero();
    nsn.compute(p);
    nsn.solve(r, u);
    benchmark::DoNotOptimize(r.data());
  }
  report(state, nsn.info(), nsn.counters());
}

/// FC/I: the global form in (v, r), or the reduction to FC/II then Newton.
template <template <class> class F>
void BM_GlobalNewton(benchmark::State& state, const char* name) {
  const GlobalProblem& p = global_problem(name);
  Vector r(p.size()), v(p.num_dofs());
  GlobalNewton<F, Coulomb3D> nsn;
  for (auto _ : state) {
    r.setZero();
    nsn.compute(p);
    nsn.solve(r, v);
    benchmark::DoNotOptimize(v.data());
  }
  report(state, nsn.info(), nsn.counters());
}
template <template <class> class F>
void BM_ReducedNewtonOnGlobal(benchmark::State& state, const char* name) {
  const GlobalProblem& p = global_problem(name);
  Vector r(p.size()), u(p.size()), v;
  Newton<F, Coulomb3D> nsn;
  double reduction_seconds = 0;
  for (auto _ : state) {
    r.setZero();
    GlobalReduction<DefaultBackend> reduction(p);
    reduction_seconds = reduction.seconds();
    nsn.compute(reduction.local());
    nsn.solve(r, u);
    v = reduction.velocity(r);
    benchmark::DoNotOptimize(v.data());
  }
  report(state, nsn.info(), nsn.counters());
  state.counters["reduction_seconds"] = reduction_seconds;
}

void register_all() {
  using benchmark::RegisterBenchmark;
  for (const char* name : {kRover, kBoxes, kCapsules, kConfeti}) {
    const std::string n = name;
    // small scenes: dense storage and dense LU, as the catalogue picks them
    if (name == kRover) {
      RegisterBenchmark(("AC/" + n).c_str(), BM_Newton<AlartCurnierFunction, DenseStorage<3>>, name, false);
      RegisterBenchmark(("FB/" + n).c_str(), BM_Newton<FischerBurmeisterFunction, DenseStorage<3>>, name, false);
      continue;
    }
    RegisterBenchmark(("AC/" + n).c_str(), BM_Newton<AlartCurnierFunction>, name, false);
    RegisterBenchmark(("JM/" + n).c_str(), BM_Newton<JeanMoreauFunction>, name, false);
    RegisterBenchmark(("NM/" + n).c_str(), BM_Newton<NaturalMapFunction>, name, false);
    RegisterBenchmark(("FB/" + n).c_str(), BM_Newton<FischerBurmeisterFunction>, name, false);
    RegisterBenchmark(("AC-hybrid/" + n).c_str(), BM_Newton<AlartCurnierFunction>, name, true);
    // the linear-solver policy: UMFPACK against Eigen's SparseLU
    RegisterBenchmark(("AC-umfpack/" + n).c_str(),
                      BM_Newton<AlartCurnierFunction, SparseStorage<3>, SparseNewtonLinearSolver<SuiteSparseBackend>>,
                      name, false);
    RegisterBenchmark(("AC-sparselu/" + n).c_str(),
                      BM_Newton<AlartCurnierFunction, SparseStorage<3>, SparseNewtonLinearSolver<EigenBackend>>,
                      name, false);
  }
  for (const char* name : {kBoxStacks, kLmgc}) {
    const std::string n = name;
    RegisterBenchmark(("global-AC/" + n).c_str(), BM_GlobalNewton<AlartCurnierFunction>, name);
    RegisterBenchmark(("global-FB/" + n).c_str(), BM_GlobalNewton<FischerBurmeisterFunction>, name);
    RegisterBenchmark(("reduced-AC/" + n).c_str(), BM_ReducedNewtonOnGlobal<AlartCurnierFunction>, name);
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
