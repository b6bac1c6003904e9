// `auto` against the entry it runs on small problems: whole registry::solve
// calls (validation, plan, stages, the recomputed FCLIB error), request made
// once, in a hot loop. On nc <= kTinyContacts `auto` runs NSGS alone, so the
// ratio auto / nsgs is its fixed cost (issue 14: at most 3x the fastest
// solver everywhere; target about 1.3x on 1-5 contacts).
//   ./build/bench/bench_auto --benchmark_min_time=0.05
// Counters: iterations of one solve, its FCLIB error.
#include "bench_support.hpp"

#include <fcsolve/solvers/catalog.hpp>

#include <memory>
#include <string>
#include <vector>

namespace {

using namespace fcsolve;

void BM_RegistrySolve(benchmark::State& state, const LocalProblem& p, const std::string& solver) {
  const registry::SolverEntry& entry = registry::find(solver);
  registry::SolveRequest req = registry::make_request(entry);
  req.common.tol = 1e-8;
  req.common.max_time = 10;
  registry::SolveOutcome out;
  for (auto _ : state) {
    out = registry::solve(p, entry, req);
    benchmark::DoNotOptimize(out.r.data());
  }
  state.counters["iterations"] = out.info.iterations;
  state.counters["error"] = out.info.error;
}

const int kRegistered = [] {
  static std::vector<std::unique_ptr<LocalProblem>> keep;
  std::vector<std::pair<std::string, const LocalProblem*>> problems;
  for (const int contacts : {1, 3, 4}) {
    keep.push_back(std::make_unique<LocalProblem>(fcsolve_bench::resting_cube(contacts)));
    problems.emplace_back("cube-" + std::to_string(contacts) + "-contacts", keep.back().get());
  }
  problems.emplace_back("Rover1039", &fcsolve_bench::local_problem("Rover1039"));
  for (const auto& [name, p] : problems)
    for (const char* solver : {"nsgs", "auto"})
      benchmark::RegisterBenchmark(("registry-small/" + name + "/" + solver).c_str(),
                                   [p = p, solver](benchmark::State& s) { BM_RegistrySolve(s, *p, solver); })
          ->Unit(benchmark::kMicrosecond);
  return 0;
}();

}  // namespace

BENCHMARK_MAIN();
