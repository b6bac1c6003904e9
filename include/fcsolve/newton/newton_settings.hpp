// Settings of the semismooth Newton solvers (newton_solver.hpp on FC/II,
// global_newton.hpp on FC/I): globalisation, rho strategy, regularisation of
// singular Newton systems and the hybrid fallback.
#pragma once

#include <fcsolve/core/enum_names.hpp>
#include <fcsolve/core/solver_settings.hpp>

namespace fcsolve {

/// Step length along the Newton direction d on the merit psi = 1/2 ||G||^2,
/// whose slope along d is -2 psi when J d = -G.
enum class LineSearch {
  None,            ///< full steps
  Armijo,          ///< backtracking: psi(r + t d) <= (1 - 2 sigma t) psi(r)
  GoldsteinPrice,  ///< Armijo plus the lower Goldstein bound (1 - 2 (1 - sigma) t) psi <= psi(r + t d) (t < 1)
};
inline constexpr EnumName<LineSearch> kLineSearchNames[] = {
    {LineSearch::GoldsteinPrice, "goldstein-price"},
    {LineSearch::Armijo, "armijo"},
    {LineSearch::None, "none"}};
constexpr const auto& enum_names(LineSearch) { return kLineSearchNames; }

/// How the per-contact rho = (rho_N, rho_T, rho_T) of the formulation is set.
enum class RhoStrategy {
  Constant,           ///< rho = settings.rho for every component
  SpectralNorm,       ///< rho = settings.rho / ||W^aa||_2
  SplitSpectralNorm,  ///< rho_N = settings.rho / W^aa_NN, rho_T = settings.rho / ||W^aa_TT||_2
  Adaptive,           ///< split spectral, times 10 then times 1/10 when Newton stalls (restart from the best iterate)
};
inline constexpr EnumName<RhoStrategy> kRhoStrategyNames[] = {
    {RhoStrategy::SplitSpectralNorm, "split-spectral"},
    {RhoStrategy::SpectralNorm, "spectral"},
    {RhoStrategy::Constant, "constant"},
    {RhoStrategy::Adaptive, "adaptive"}};
constexpr const auto& enum_names(RhoStrategy) { return kRhoStrategyNames; }

struct NewtonSettings : SolverSettings {
  LineSearch line_search = LineSearch::GoldsteinPrice;
  double sigma = 1e-4;        ///< sufficient-decrease parameter (Armijo, Goldstein-Price)
  int max_line_search = 30;   ///< trial steps per iteration (halving)
  /// Nonmonotone Armijo test against the largest of the last
  /// `line_search_memory` merits (1: monotone; at most 16).
  int line_search_memory = 10;
  double min_step = 1e-10;    ///< a step length below this is a line-search failure
  /// After a failed line search take the full step anyway (Siconos' NSN
  /// does); the best iterate is kept and returned if the solve fails.
  bool nonmonotone = true;
  RhoStrategy rho_strategy = RhoStrategy::SplitSpectralNorm;
  double rho = 1.0;           ///< the constant rho, or the factor on the spectral values
  /// Every Newton system is shifted, (J + delta I) d = -G, with the
  /// Levenberg-Marquardt-like delta = levenberg_marquardt * max(1, max|J_ii|)
  /// * min(1, ||G|| / ||G(r = 0)||): it tames rank-deficient W and vanishes
  /// at the solution (0: plain Newton).
  double levenberg_marquardt = 0.1;
  /// A system that is still singular is retried with delta =
  /// singular_regularization * max(1, max|J_ii|), grown 100x per failure.
  double singular_regularization = 1e-10;
  /// Stall: the best error does not drop by `stall_ratio` within
  /// `stall_window` iterations (or no Newton step can be computed). Then the
  /// solve restarts from the best iterate: with a rescaled rho (Adaptive),
  /// else with Gauss-Seidel sweeps (local Alart-Curnier solves) until the
  /// error drops by `resume_ratio` or `fallback_sweeps` are done (hybrid),
  /// else it stops with Status::Stalled.
  int stall_window = 500;
  double stall_ratio = 0.5;
  bool hybrid = false;
  int fallback_sweeps = 100;
  double resume_ratio = 0.1;
};

}  // namespace fcsolve
