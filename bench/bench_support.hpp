// Shared by the Google Benchmark programs in bench/: the FCLIB problems they
// run on and reproducible inputs.
#pragma once

#include <fcsolve/io/fclib.hpp>

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <map>
#include <random>
#include <string>

namespace fcsolve_bench {

/// Set by CMake in the generated bench_paths.cpp (bench/bench_paths.cpp.in).
namespace paths {
extern const char* const bundled_data;  // examples/data
extern const char* const shared_data;   // ../shared/data/fclib beside the checkout
}  // namespace paths

/// Folder of the problems: $FCSOLVE_BENCH_DATA, else the bundled examples/data.
inline std::string data_dir() {
  if (const char* env = std::getenv("FCSOLVE_BENCH_DATA"); env && *env) return env;
  return paths::bundled_data;
}

inline std::string data_file(const std::string& name) { return data_dir() + "/" + name + ".hdf5"; }

/// A problem read once per program (benchmarks re-run their body many times).
inline const fcsolve::LocalProblem& local_problem(const std::string& name) {
  static std::map<std::string, fcsolve::LocalProblem> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, fcsolve::fclib::read_local(data_file(name))).first;
  return it->second;
}
inline const fcsolve::GlobalProblem& global_problem(const std::string& name) {
  static std::map<std::string, fcsolve::GlobalProblem> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, fcsolve::fclib::read_global(data_file(name))).first;
  return it->second;
}

/// Reproducible standard-normal entries.
inline fcsolve::Vector random_vector(fcsolve::Index n, unsigned seed = 1) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> normal;
  fcsolve::Vector x(n);
  for (fcsolve::Index k = 0; k < n; ++k) x[k] = normal(gen);
  return x;
}

/// A rate counter: `per_iteration` things (contacts, nonzeros, ...) per
/// benchmark iteration, reported per second.
inline void rate(benchmark::State& state, const char* name, double per_iteration) {
  state.counters[name] =
      benchmark::Counter(per_iteration, benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace fcsolve_bench
