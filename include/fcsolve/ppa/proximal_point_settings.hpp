// Settings of the proximal point method (ppa/proximal_point.hpp).
#pragma once

#include <fcsolve/core/solver_settings.hpp>

#include <type_traits>
#include <utility>

namespace fcsolve {

/// Outer knobs of ProximalPoint; `InnerSettings` are the inner solver's own
/// (line search, NSGS ordering, ...). tol, max_iter, max_time, callback and
/// history are the outer solve's: each inner solve gets its tolerance, its
/// iteration cap and the time left from the outer loop, and no callback.
template <class InnerSettings>
struct ProximalPointSettings : SolverSettings {
  /// alpha = sigma err^nu (times the factor of the failure / fast-success
  /// rule), in units of mean |W_ii|; Siconos' PROX defaults (sigma = 5,
  /// nu = 1; Acary, Bremond & Huber 2018, sec. on the proximal point method).
  double sigma = 5.0;
  double nu = 1.0;
  /// alpha is kept in [alpha_min, alpha_max] (units of mean |W_ii|): a
  /// positive floor keeps W + alpha I regular on rank-deficient W.
  double alpha_min = 1e-8;
  double alpha_max = 1e6;
  /// An inner solve that succeeds in at most this many iterations and
  /// lowers the outer error divides the factor on alpha by 10 (a failed one
  /// multiplies it by 10).
  int fast_inner_iterations = 3;
  int inner_max_iter = 100;  ///< iteration cap of each inner solve
  /// An inner Newton solve whose best error does not halve within this many
  /// iterations stops as stalled, a failed subproblem (alpha grows tenfold),
  /// instead of running on to inner_max_iter: near the solution of a
  /// rank-deficient W the subproblems at small alpha can be as hard for
  /// Newton as the problem itself, and each such failure cost 100 Newton
  /// steps (measured on generated walls and sphere piles of 1000 to 3000
  /// contacts). 0: the inner solver's own setting. Inner solvers without a
  /// stall window (NSGS) ignore it.
  int inner_stall_window = 20;
  InnerSettings inner;
};

/// Whether an inner solver's settings have a Newton stall window.
template <class S, class = void>
struct has_stall_window : std::false_type {};
template <class S>
struct has_stall_window<S, std::void_t<decltype(std::declval<S&>().stall_window)>> : std::true_type {};

}  // namespace fcsolve
