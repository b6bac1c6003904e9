// The one-call entry point: fcsolve::solve(problem, settings) solves FC/II
// (LocalProblem) or FC/I (GlobalProblem) with the catalogue's `auto` plan
// (solvers/auto_entries.hpp) unless another solver is named.
//
//   #include <fcsolve/solve.hpp>
//   fcsolve::SolveSettings s;   // tol 1e-8, no time limit
//   s.max_time = 10;
//   const fcsolve::Solution sol = fcsolve::solve(problem, s);
//   if (sol.info.converged()) use(sol.r, sol.u, sol.v);
//
// Header-only over the catalogue: including it instantiates every
// registered solver (compile time); a program that needs one solver only
// includes that family's header (nsgs.hpp, newton.hpp, nipm.hpp) instead.
#pragma once

#include <fcsolve/solvers/catalog.hpp>

#include <string>

namespace fcsolve {

/// r, u (and v, lambda for FC/I), info (status, error, iterations, message)
/// and, for `auto`, the stages it ran.
using Solution = registry::SolveOutcome;

struct SolveSettings : SolverSettings {
  /// With `auto`, max_iter bounds the iterations of all stages together.
  SolveSettings() { max_iter = 1000000; }
  std::string solver = "auto";  ///< any name of `fcsolve solvers`
  Vector r0;                    ///< warm start for r (empty: the solver's own)
  Vector v0;                    ///< warm start for v (FC/I, global-native solvers)
};

namespace detail {
inline registry::SolveRequest request_for(const SolveSettings& s) {
  registry::SolveRequest req = registry::make_request(registry::find(s.solver));
  req.common = s;  // the SolverSettings part: tol, max_iter, max_time, history, callback
  req.r0 = s.r0;
  req.v0 = s.v0;
  return req;
}
}  // namespace detail

/// Solves FC/II. `converged` only if the FCLIB error of the returned r is
/// <= tol (recomputed by the registry); bad input throws InvalidProblem.
inline Solution solve(const LocalProblemView& problem, const SolveSettings& settings = {}) {
  return registry::solve(problem, registry::find(settings.solver), detail::request_for(settings));
}
inline Solution solve(const LocalProblem& problem, const SolveSettings& settings = {}) {
  return solve(LocalProblemView(problem), settings);
}

/// Solves FC/I (natively or by reduction, as the solver does; `auto` reduces
/// once and recovers v).
inline Solution solve(const GlobalProblemView& problem, const SolveSettings& settings = {}) {
  return registry::solve(problem, registry::find(settings.solver), detail::request_for(settings));
}
inline Solution solve(const GlobalProblem& problem, const SolveSettings& settings = {}) {
  return solve(GlobalProblemView(problem), settings);
}

}  // namespace fcsolve
