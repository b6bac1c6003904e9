// Interior-point family on the FCLIB global problems (the shared collection
// beside the checkout, or examples/data): the NIPM, the ACLM Newton and
// fixed-point loops and the convex SOCQP IPM (s = 0), each compute() + solve()
// per benchmark iteration, with counters
//   iterations       interior-point iterations of the solve
//   factorizations   Newton matrices factorised
//   factor_share     time in assembling + factorising them / total time
//   error            FCLIB error of the result (frozen-s error for socqp)
//   converged        1 if error <= tol (1e-8; 1e-12 for socqp)
// Siconos side by side: bench/compare_siconos.py --group ipm.
//   build/bench/bench_ipm --benchmark_min_time=0.01
#include <fcsolve/io/fclib.hpp>
#include <fcsolve/nipm.hpp>

#include "bench_support.hpp"

#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace fcsolve;
using namespace fcsolve::ipm;

std::vector<std::string> global_files() {
  namespace fs = std::filesystem;
  std::vector<std::string> out;
  const fs::path shared = fs::path(fcsolve_bench::paths::shared_data) / "global";
  if (fs::is_directory(shared)) {
    for (const auto& e : fs::directory_iterator(shared))
      if (e.path().extension() == ".hdf5") out.push_back(e.path().string());
  } else {
    for (const auto& e : fs::directory_iterator(fcsolve_bench::paths::bundled_data))
      if (e.path().extension() == ".hdf5" && fclib::detect_kind(e.path().string()) == fclib::Kind::Global)
        out.push_back(e.path().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// compute() + solve() of Solver (a GlobalSocqpIpm, GlobalAclm or GlobalNipm).
template <class Solver, class Settings>
void run_solver(benchmark::State& state, const std::shared_ptr<GlobalProblem>& g, Settings settings) {
  SolverInfo info;
  IpmStatistics stats;
  double seconds = 0;
  for (auto _ : state) {
    Stopwatch clock;
    Solver solver(settings);
    solver.compute(*g);
    Vector r = Vector::Zero(g->size()), v(g->num_dofs());
    info = solver.solve(r, v);
    seconds = clock.seconds();
    stats = solver.statistics();
    benchmark::DoNotOptimize(r.data());
  }
  state.counters["iterations"] = info.iterations;
  state.counters["factorizations"] = stats.factorizations;
  state.counters["factor_share"] = seconds > 0 ? stats.factor_seconds / seconds : 0.0;
  state.counters["error"] = info.error;
  state.counters["converged"] = info.converged() ? 1 : 0;
}

/// Dense Newton matrices for tiny scenes, as the catalogue chooses.
template <template <class, class> class Alias, class Settings>
void run_sized(benchmark::State& state, const std::shared_ptr<GlobalProblem>& g, const Settings& s) {
  if (g->num_dofs() + g->size() <= 96)
    run_solver<Alias<Coulomb3D, DenseKktFactorization>>(state, g, s);
  else
    run_solver<Alias<Coulomb3D, SparseKktFactorization<DefaultBackend>>>(state, g, s);
}

const bool registered = [] {
  for (const auto& path : global_files()) {
    auto g = std::make_shared<GlobalProblem>(std::get<GlobalProblem>(fclib::read_problem(path)));
    if (g->d != 3 || g->has_bilateral()) continue;
    const std::string name = std::filesystem::path(path).stem().string();
    NipmSettings nipm;
    AclmSettings newton, fixed_point;
    fixed_point.variant = AclmVariant::FixedPoint;
    IpmSettings socqp;
    socqp.tol = 1e-12;
    benchmark::RegisterBenchmark(("nipm/" + name).c_str(), [g, nipm](benchmark::State& st) {
      run_sized<GlobalNipm>(st, g, nipm);
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("aclm-newton/" + name).c_str(), [g, newton](benchmark::State& st) {
      run_sized<GlobalAclm>(st, g, newton);
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("aclm-fp/" + name).c_str(), [g, fixed_point](benchmark::State& st) {
      run_sized<GlobalAclm>(st, g, fixed_point);
    })->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("ipm-socqp/" + name).c_str(), [g, socqp](benchmark::State& st) {
      run_sized<GlobalSocqpIpm>(st, g, socqp);
    })->Unit(benchmark::kMillisecond);
  }
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
