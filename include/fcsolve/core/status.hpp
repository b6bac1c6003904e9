// Outcome of a solve, shared by every solver.
#pragma once

namespace fcsolve {

/// What a solver achieved. Only Converged means the error (fcsolve's FCLIB
/// definition, problem/error.hpp) is within the requested tolerance.
enum class Status {
  NotRun,          ///< solve() was not called, or compute() failed
  Converged,       ///< error <= tol, checked with the full error measure
  MaxIterations,   ///< iteration budget spent
  TimeLimit,       ///< wall-clock budget spent
  Stalled,         ///< no progress for a while (line search failed, ...)
  Diverged,        ///< the error grew beyond recovery
  NumericalError,  ///< NaN/Inf appeared or a factorisation failed
  Stopped,         ///< the user's callback asked to stop
};

/// The stable token of a status, as the CLI (text and JSON), the Python
/// `Result.status` and the campaign CSVs write it (ipm::IpmExit's tokens
/// follow it). NumericalError is "nan": the token is data, not prose, and
/// python/tests/test_solve.py, the
/// campaign's failure classes (campaign/results.py, tasks.py, charts.py), the
/// Siconos runner's output and every results.csv already written use "nan";
/// renaming it would split one failure class in two across old and new runs.
inline const char* to_string(Status s) noexcept {
  switch (s) {
    case Status::NotRun: return "not-run";
    case Status::Converged: return "converged";
    case Status::MaxIterations: return "max-iterations";
    case Status::TimeLimit: return "timeout";
    case Status::Stalled: return "stalled";
    case Status::Diverged: return "diverged";
    case Status::NumericalError: return "nan";
    case Status::Stopped: return "stopped";
  }
  return "unknown";
}

}  // namespace fcsolve
