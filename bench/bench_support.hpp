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

/// A rigid cube (mass 1, inertia 1/6 I) resting on `contacts` (1 to 4) of
/// its bottom corners after one step of h = 0.01 under gravity, sliding
/// sideways at 0.05 m/s (mu = 0.3): W = H^T M^-1 H, q = H^T v_free. The
/// small scene of a real-time engine.
inline fcsolve::LocalProblem resting_cube(int contacts) {
  using namespace fcsolve;
  const Eigen::Vector3d corners[] = {{0.5, 0.5, -0.5}, {-0.5, 0.5, -0.5}, {-0.5, -0.5, -0.5},
                                     {0.5, -0.5, -0.5}};
  const Eigen::Vector3d frame[] = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(),
                                   Eigen::Vector3d::UnitY()};
  DenseMatrix H(6, 3 * contacts);  // column: (e, p x e), u = e . (v + omega x p)
  for (int a = 0; a < contacts; ++a)
    for (int k = 0; k < 3; ++k) H.col(3 * a + k) << frame[k], corners[a].cross(frame[k]);
  Vector Minv(6);
  Minv << 1, 1, 1, 6, 6, 6;
  Vector v_free(6);
  v_free << 0.05, 0, -9.81 * 0.01, 0, 0, 0;
  LocalProblem p;
  p.d = 3;
  p.W = (H.transpose() * Minv.asDiagonal() * H).sparseView();
  p.W.makeCompressed();
  p.q = H.transpose() * v_free;
  p.mu = Vector::Constant(contacts, 0.3);
  return p;
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
