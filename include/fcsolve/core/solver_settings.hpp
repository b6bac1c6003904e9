// Settings and information every fcsolve solver shares. A solver's own
// settings struct derives from SolverSettings and adds its knobs with member
// defaults (no long constructors); its info() returns a SolverInfo.
#pragma once

#include <fcsolve/core/status.hpp>

#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace fcsolve {

/// Passed to the per-iteration callback.
struct IterationInfo {
  int iteration = 0;        ///< 1-based iteration (sweep, Newton step, ...)
  double error = 0;         ///< last error estimate
  bool full_error = false;  ///< true when `error` is the full FCLIB error
  double seconds = 0;       ///< time since solve() started
};

/// Called after each iteration. SciPy's convention (scipy.optimize.minimize,
/// `callback`): return true to stop the solve (Status::Stopped), false to go on.
using IterationCallback = std::function<bool(const IterationInfo&)>;

struct SolverSettings {
  double tol = 1e-8;  ///< target FCLIB relative error (problem/error.hpp)
  int max_iter = 1000;
  double max_time = std::numeric_limits<double>::infinity();  ///< seconds
  bool record_history = false;  ///< keep the error of every iteration in info().history
  IterationCallback callback;   ///< called once per iteration when set; true stops
};

/// True when a callback is set and asks to stop (returns true).
inline bool callback_requests_stop(const IterationCallback& callback, const IterationInfo& it) {
  return callback && callback(it);
}

struct SolverInfo {
  Status status = Status::NotRun;
  int iterations = 0;
  double error = std::numeric_limits<double>::infinity();  ///< FCLIB error of the returned r
  double setup_seconds = 0;  ///< compute(): factorisations, caches
  double solve_seconds = 0;  ///< solve()
  std::vector<double> history;  ///< per-iteration error if record_history
  std::string message;          ///< what the solver did (fallbacks, regularisation, ...)
  bool converged() const { return status == Status::Converged; }
};

}  // namespace fcsolve
