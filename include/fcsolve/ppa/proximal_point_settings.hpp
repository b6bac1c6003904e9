// Settings of the proximal point method (ppa/proximal_point.hpp).
#pragma once

#include <fcsolve/core/solver_settings.hpp>

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
  /// An inner solve that succeeds in at most this many iterations divides
  /// the factor on alpha by 10 (a failed one multiplies it by 10).
  int fast_inner_iterations = 3;
  int inner_max_iter = 100;  ///< iteration cap of each inner solve
  InnerSettings inner;
};

}  // namespace fcsolve
