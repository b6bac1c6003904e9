// Settings of the ADMM solver (admm_solver.hpp): the penalty rho, how it is
// chosen and adapted, over-relaxation, acceleration and the refactorisation cap.
#pragma once

#include <fcsolve/core/enum_names.hpp>
#include <fcsolve/core/solver_settings.hpp>

namespace fcsolve {

/// Where rho starts.
enum class AdmmRhoInit {
  Given,     ///< rho0 = settings.rho
  Spectral,  ///< rho0 = rho sqrt(L m) (L/m)^0.2, L = lambda_max(W_s) by power iteration, m = min_i W_ii
};
inline constexpr EnumName<AdmmRhoInit> kAdmmRhoInitNames[] = {
    {AdmmRhoInit::Given, "given"}, {AdmmRhoInit::Spectral, "spectral"}};
constexpr const auto& enum_names(AdmmRhoInit) { return kAdmmRhoInitNames; }

/// How rho changes during the solve (every `adapt_interval` iterations; each
/// change refactorises W + rho I, at most `max_refactorizations` times).
enum class AdmmRhoStrategy {
  Constant,           ///< rho0 throughout: one factorisation
  ResidualBalancing,  ///< x2 / /2 when r_p / r_d leaves [1/10, 10] (Boyd et al. 2011, eq. 3.13)
  Osqp,               ///< rho * sqrt(r_p / r_d) when that factor leaves [1/5, 5] (Stellato et al. 2020, sec. 5.2)
};
inline constexpr EnumName<AdmmRhoStrategy> kAdmmRhoStrategyNames[] = {
    {AdmmRhoStrategy::ResidualBalancing, "residual-balancing"},
    {AdmmRhoStrategy::Osqp, "osqp"},
    {AdmmRhoStrategy::Constant, "constant"}};
constexpr const auto& enum_names(AdmmRhoStrategy) { return kAdmmRhoStrategyNames; }

struct AdmmSettings : SolverSettings {
  /// Given (rho0 = 1, Siconos' default) measured better than the spectral
  /// rho0, which comes out far too large on stacks (1e3 on BoxesStack1).
  AdmmRhoInit rho_init = AdmmRhoInit::Given;
  AdmmRhoStrategy rho_strategy = AdmmRhoStrategy::ResidualBalancing;
  double rho = 1.0;            ///< rho0 when rho_init = Given; a factor on the spectral rho0 otherwise
  double relaxation = 1.0;     ///< over-relaxation alpha in [1, 1.8] (1: none)
  bool acceleration = true;    ///< Nesterov's extrapolation with restart (Goldstein et al. 2014, alg. 8)
  double restart_factor = 0.999;  ///< eta: restart when the combined residual grows past c_{k-1} / eta
  /// iterations between two rho updates (30 measured better than 10 on the
  /// Capsules: fewer refactorisations, rho settles; docs/results.md)
  int adapt_interval = 30;
  int max_refactorizations = 40;  ///< rho is frozen after this many refactorisations
  int power_iterations = 30;   ///< for L = lambda_max(W) of the spectral rho0
};

}  // namespace fcsolve
