// The two rules both ADMM solvers (admm_solver.hpp on FC/II, admm_global.hpp
// on FC/I) share: how rho follows the residuals, and Nesterov's
// extrapolation with restart.
#pragma once

#include <fcsolve/admm/admm_settings.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fcsolve {

/// The factor on rho from the relative primal and dual residuals (1: keep
/// rho). Residual balancing: x2 / /2 when r_p / r_d leaves [1/10, 10] (Boyd
/// et al. 2011, eq. 3.13); OSQP: sqrt(r_p / r_d) when it leaves [1/5, 5]
/// (Stellato et al. 2020, sec. 5.2).
inline double admm_rho_factor(AdmmRhoStrategy strategy, double rp, double rd) {
  if (strategy == AdmmRhoStrategy::Constant) return 1;
  if (!(rp > 0 && rd > 0) || !std::isfinite(rp / rd)) return 1;
  if (strategy == AdmmRhoStrategy::ResidualBalancing) {
    if (rp > 10 * rd) return 2;
    if (rd > 10 * rp) return 0.5;
    return 1;
  }
  const double f = std::sqrt(rp / rd);
  return f > 5 || f < 0.2 ? f : 1;
}

/// The FCLIB error, since the extrapolation last restarted, past this
/// multiple of its least value restarts it (AdmmMomentum::error_grew).
inline constexpr double kMomentumErrorGrowth = 2;

/// Nesterov's extrapolation with restart of Goldstein, O'Donoghue, Setzer &
/// Baraniuk 2014 (alg. 8) on the combined residual c_k.
class AdmmMomentum {
 public:
  explicit AdmmMomentum(double restart_factor) : eta_(restart_factor) {}

  /// True when the FCLIB error has grown past kMomentumErrorGrowth times
  /// its least value since the restart: the caller restarts. Alg. 8's
  /// test watches the combined residual only, which on a De Saxce-shifted
  /// (nonconvex) problem can keep falling while beta -> 1 lets a mode
  /// grow: on a pile of 10^4 spheres the error rose 0.8 % an iteration
  /// for 800 iterations, 5.5e-6 -> 2.5e-3, with no restart.
  bool error_grew(double error) {
    least_error_ = std::min(least_error_, error);
    return error > kMomentumErrorGrowth * least_error_;
  }

  /// beta >= 0 to extrapolate x^ = x + beta (x - x_prev) when c fell below
  /// c_{k-1} / eta; a negative value to restart from x_prev.
  double step(double combined) {
    if (combined < eta_ * combined_prev_) {
      const double a_next = 0.5 * (1 + std::sqrt(1 + 4 * a_ * a_));
      const double beta = (a_ - 1) / a_next;
      a_ = a_next;
      combined_prev_ = combined;
      return beta;
    }
    a_ = 1;
    combined_prev_ /= eta_;
    return -1;
  }

 private:
  double eta_;
  double least_error_ = std::numeric_limits<double>::infinity();
  double a_ = 1;
  double combined_prev_ = std::numeric_limits<double>::infinity();
};

}  // namespace fcsolve
