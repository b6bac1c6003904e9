// The iteration both ADMM solvers run (CRTP): Admm on FC/II
// (admm_solver.hpp) and AdmmGlobal on FC/I (admm_global.hpp) differ in
// their linear system, their variables and their residuals' units, not in
// the loop: a step, the best iterate kept by its FCLIB error, Nesterov's
// extrapolation with restart (admm_rules.hpp), the budgets and the callback,
// rho adapted every adapt_interval iterations. A factorisation cannot be
// interrupted, so one that would not end within max_time (at the time the
// last one took) is not started: rho stays, and the balancing of the best
// iterate's velocity after an unconverged solve (AdmmGlobal) is skipped.
// The derived class provides
//   double step(double& primal_sq, double& dual_sq)  one iteration; its FCLIB error
//   void save_best()                                 keep the current iterate
//   double combined_residual(double dual_sq)         c_k of the restart rule
//   AdmmPoint point()                                the two halves of the ADMM point
//   bool adapt_rho(double primal_sq, double dual_sq) true if rho changed
//   bool factorize(double rho)                       the rho system; false if it failed
//   void finish_solve()                              after the last iteration
//   static constexpr const char* kFactorizationFailure
#pragma once

#include <fcsolve/admm/admm_rules.hpp>
#include <fcsolve/admm/admm_settings.hpp>
#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/core/timer.hpp>

#include <algorithm>
#include <cmath>

namespace fcsolve {

/// The ADMM point's two halves (z, xi) on FC/II, (xi, r) on FC/I: each with
/// the extrapolated point the next step starts from and the previous one.
struct AdmmPoint {
  Vector *x, *x_hat, *x_prev, *y, *y_hat, *y_prev;
};

template <class Derived>
class AdmmLoop {
 public:
  using Settings = AdmmSettings;

  explicit AdmmLoop(const Settings& s) : settings_(s) {}
  Settings& settings() { return settings_; }
  const Settings& settings() const { return settings_; }
  const SolverInfo& info() const { return info_; }
  /// rho at the end of the last solve (after adaptation), and how many
  /// factorisations of the rho system that solve used (1: rho never changed).
  /// (AdmmGlobal refactorises M after an unconverged solve; its rho_ then
  /// reads 0, the value kept here does not.)
  double rho() const { return last_rho_; }
  int factorizations() const { return factorizations_; }

 protected:
  /// The per-solve info reset, rho back to rho0.
  void begin_solve() {
    info_.status = Status::MaxIterations;
    info_.iterations = 0;
    info_.history.clear();
    info_.message.clear();
    if (rho_ != rho0_) factorization_ok_ = refactorize(rho0_);
    factorizations_ = 1;  // the cap counts this solve's factorisations, the one in use included
  }

  /// Iterates from the current point, of FCLIB error `error`, then sets
  /// the status (converged only if the best error is within tol) and the
  /// solve time.
  void run(double error, const Stopwatch& clock) {
    best_error_ = error;
    self().save_best();
    if (!factorization_ok_) {
      info_.status = Status::NumericalError;
      info_.message = Derived::kFactorizationFailure;
    } else if (error > settings_.tol) {
      iterate(clock);
    }
    last_rho_ = rho_;
    if (factorization_fits(clock)) self().finish_solve();
    if (best_error_ <= settings_.tol) info_.status = Status::Converged;
    info_.error = best_error_;
    info_.solve_seconds = clock.seconds();
  }

  bool refactorize(double rho) {
    rho_ = rho;
    ++factorizations_;
    const Stopwatch clock;
    const bool ok = self().factorize(rho);
    factorization_seconds_ = clock.seconds();
    return ok;
  }

  /// Whether one more factorisation, at the time the last one took, ends
  /// within max_time.
  bool factorization_fits(const Stopwatch& clock) const {
    return clock.seconds() + factorization_seconds_ <= settings_.max_time;
  }

  Settings settings_;
  SolverInfo info_;
  double rho0_ = 1, rho_ = 1, last_rho_ = 0, best_error_ = 0;
  double factorization_seconds_ = 0;  ///< of the last refactorize()
  int factorizations_ = 0;
  bool factorization_ok_ = false;

 private:
  Derived& self() { return static_cast<Derived&>(*this); }

  void iterate(const Stopwatch& clock) {
    AdmmMomentum momentum(settings_.restart_factor);
    restart_extrapolation(momentum);
    for (int k = 1; k <= settings_.max_iter; ++k) {
      info_.iterations = k;
      FCSOLVE_NO_MALLOC_BEGIN();
      double primal_sq = 0, dual_sq = 0;
      const double error = self().step(primal_sq, dual_sq);
      if (error < best_error_) {
        best_error_ = error;
        self().save_best();
      }
      if (momentum.error_grew(error)) restart_extrapolation(momentum);
      else extrapolate(momentum, dual_sq);
      FCSOLVE_NO_MALLOC_END();
      if (!std::isfinite(error)) {
        info_.status = Status::NumericalError;
        break;
      }
      if (settings_.record_history) info_.history.push_back(error);
      if (error <= settings_.tol) break;
      if (callback_requests_stop(settings_.callback, IterationInfo{k, error, true, clock.seconds()})) {
        info_.status = Status::Stopped;
        break;
      }
      if (clock.seconds() > settings_.max_time) {
        info_.status = Status::TimeLimit;
        break;
      }
      if (k % std::max(1, settings_.adapt_interval) == 0 && factorization_fits(clock) &&
          self().adapt_rho(primal_sq, dual_sq)) {
        if (!factorization_ok_) {
          info_.status = Status::NumericalError;
          info_.message = Derived::kFactorizationFailure;
          break;
        }
        restart_extrapolation(momentum);  // the old momentum was built with another rho
      }
    }
  }

  /// Goldstein et al. 2014, alg. 8: extrapolate while the combined residual
  /// falls, restart from the previous point when not; without acceleration
  /// the next step starts from the point itself.
  void extrapolate(AdmmMomentum& m, double dual_sq) {
    const AdmmPoint p = self().point();
    if (!settings_.acceleration) {
      *p.x_hat = *p.x;
      *p.y_hat = *p.y;
      return;
    }
    const double beta = m.step(self().combined_residual(dual_sq));
    if (beta >= 0) {
      *p.x_hat = *p.x + beta * (*p.x - *p.x_prev);
      *p.y_hat = *p.y + beta * (*p.y - *p.y_prev);
    } else {
      *p.x_hat = *p.x_prev;
      *p.y_hat = *p.y_prev;
    }
  }

  /// Extrapolation restarted from the current point.
  void restart_extrapolation(AdmmMomentum& m) {
    m = AdmmMomentum(settings_.restart_factor);
    const AdmmPoint p = self().point();
    *p.x_hat = *p.x;
    *p.y_hat = *p.y;
    *p.x_prev = *p.x;
    *p.y_prev = *p.y;
  }
};

}  // namespace fcsolve
