// The outer loop shared by the reduced and the global Newton solvers: stop
// tests, history and callback, the best iterate, stall detection and what
// follows a stall (adaptive rho, hybrid fallback sweeps, or Status::Stalled).
// Derived's error(), fallback_sweep() and the steps outside the
// factorisation allocate nothing (FCSOLVE_NO_MALLOC_BEGIN/END, proved by
// tests/test_newton_nomalloc.cpp). CRTP: Derived provides
//   double error()          FCLIB error of the current iterate
//   bool newton_step()      one globalised step (false: no step possible)
//   void save_best(), restore_best()
//   void refresh()          recompute G and its Jacobian at the current iterate
//   void set_rho_factor(double)
//   bool fallback_sweep()   one fallback sweep (false: the form has none)
#pragma once

#include <fcsolve/core/exceptions.hpp>
#include <fcsolve/core/solver_settings.hpp>
#include <fcsolve/core/timer.hpp>
#include <fcsolve/newton/line_search.hpp>
#include <fcsolve/newton/newton_settings.hpp>
#include <fcsolve/newton/newton_step.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace fcsolve {

template <class Derived>
class NewtonLoop {
 public:
  NewtonSettings& settings() { return settings_; }
  const NewtonSettings& settings() const { return settings_; }
  const SolverInfo& info() const { return info_; }
  /// What the last solve did (Newton steps, fallback sweeps, factorisations).
  const NewtonCounters& counters() const { return counters_; }

 protected:
  explicit NewtonLoop(const NewtonSettings& s) : settings_(s) {}

  /// A problem of another pattern: the last step's duration says nothing
  /// about its steps. Solves of one pattern (the proximal point's
  /// subproblems) keep it, so that a subproblem's first step is not started
  /// past the budget either.
  void forget_step_time() { step_seconds_ = 0; }

  static void check_dimension(int problem_d, int solver_d) {
    if (problem_d != solver_d)
      throw InvalidProblem("spacedim", "problem has d = " + std::to_string(problem_d) +
                                           ", solver was built for d = " + std::to_string(solver_d));
  }

  /// The shift of the Newton system at merit psi (newton_settings.hpp).
  double shift(double psi, double reference_norm) const {
    return settings_.levenberg_marquardt * std::min(1.0, std::sqrt(2 * psi) / reference_norm);
  }

  /// The step length along a Newton direction whose merit is merit(t): the
  /// line search's, else (no sufficient decrease) the full nonmonotone step
  /// Siconos' NSN takes, if allowed and finite (the best iterate is kept
  /// aside by run()); 0: no step.
  template <class Merit>
  double step_length(double psi, Merit&& merit) {
    // the reference of the nonmonotone Armijo test: max of the last merits
    recent_[recent_next_++ % recent_.size()] = psi;
    const int memory = std::clamp(settings_.line_search_memory, 1, int(recent_.size()));
    double reference = psi;
    for (int k = 1; k < std::min(memory, recent_next_); ++k)
      reference = std::max(reference, recent_[(recent_next_ - 1 - k) % recent_.size()]);
    const LineSearchResult ls = line_search(settings_, psi, merit, reference);
    const bool full = !ls.accepted && settings_.nonmonotone && std::isfinite(merit(1.0));
    counters_.line_search_trials += ls.trials;
    if (!ls.accepted && !full) return 0;
    if (full) ++counters_.nonmonotone_steps;
    ++counters_.steps;
    return ls.accepted ? ls.step : 1.0;
  }

  /// Runs the iteration from the derived class's current iterate; on return
  /// that iterate is the solution or, after a failure, the best one seen.
  void run(const Stopwatch& clock) {
    Derived& self = static_cast<Derived&>(*this);
    info_.status = Status::MaxIterations;
    info_.iterations = 0;
    info_.history.clear();
    info_.message.clear();
    counters_ = NewtonCounters();
    recent_next_ = 0;
    double kappa = 1;  // adaptive rho factor
    int rho_retries = 0;
    self.set_rho_factor(kappa);
    self.refresh();
    double error = self.error();
    // The best iterate is what a failed solve returns. A stall is a window of
    // stall_window iterations in which the best error does not drop by
    // stall_ratio; the solve then restarts from the best iterate.
    self.save_best();
    double best = error, reference = error;
    int since = 0;
    auto track = [&](double e) {
      if (e < best) {
        best = e;
        self.save_best();
      }
      if (best <= settings_.stall_ratio * reference) {
        reference = best;
        since = 0;
      } else {
        ++since;
      }
    };
    while (true) {
      if (!std::isfinite(error)) { info_.status = Status::NumericalError; break; }
      if (error <= settings_.tol) { info_.status = Status::Converged; break; }
      if (info_.iterations >= settings_.max_iter) { info_.status = Status::MaxIterations; break; }
      // A step is not started when the last one says it would end past the
      // budget: a factorisation cannot be interrupted once begun.
      if (clock.seconds() + step_seconds_ > settings_.max_time) { info_.status = Status::TimeLimit; break; }
      ++info_.iterations;
      const double step_start = clock.seconds();
      const bool moved = self.newton_step();
      step_seconds_ = clock.seconds() - step_start;
      if (moved) {
        FCSOLVE_NO_MALLOC_BEGIN();
        error = self.error();
        FCSOLVE_NO_MALLOC_END();
        track(error);
        if (!record(error, clock)) break;
      }
      if (moved && (settings_.stall_window <= 0 || since < settings_.stall_window)) continue;
      // stalled: restart from the best iterate, with another rho or the sweeps
      since = 0;
      recent_next_ = 0;
      reference = best;
      self.restore_best();
      error = best;
      if (settings_.rho_strategy == RhoStrategy::Adaptive && rho_retries < 2) {
        kappa *= rho_retries++ == 0 ? 10.0 : 0.01;  // try 10 rho, then rho / 10
        self.set_rho_factor(kappa);
        ++counters_.rho_changes;
      } else if (settings_.hybrid && run_fallback(error, clock)) {
        track(error);
        if (info_.status == Status::Stopped) break;
      } else {
        info_.status = Status::Stalled;
        break;
      }
      self.refresh();
    }
    if (!(error <= best) && info_.status != Status::Converged) {
      self.restore_best();
      error = best;
    }
    info_.error = error;
    info_.message = counters_.describe();
  }

  NewtonSettings settings_;
  SolverInfo info_;
  NewtonCounters counters_;

 private:
  std::array<double, 16> recent_{};  // last merits (nonmonotone line search)
  double step_seconds_ = 0;           // the last Newton step's duration
  int recent_next_ = 0;

  /// Fallback sweeps until the error drops by resume_ratio; false if the
  /// derived form has no fallback.
  bool run_fallback(double& error, const Stopwatch& clock) {
    Derived& self = static_cast<Derived&>(*this);
    ++counters_.fallbacks;
    const double target = settings_.resume_ratio * error;
    for (int s = 0; s < settings_.fallback_sweeps; ++s) {
      if (error <= settings_.tol || error <= target) break;
      if (info_.iterations >= settings_.max_iter || clock.seconds() > settings_.max_time) break;
      FCSOLVE_NO_MALLOC_BEGIN();
      const bool swept = self.fallback_sweep();
      if (swept) error = self.error();
      FCSOLVE_NO_MALLOC_END();
      if (!swept) return false;
      ++info_.iterations;
      ++counters_.sweeps;
      if (!record(error, clock)) break;
    }
    return true;
  }

  /// History and callback; false when the callback asks to stop.
  bool record(double error, const Stopwatch& clock) {
    if (settings_.record_history) info_.history.push_back(error);
    if (callback_requests_stop(settings_.callback,
                               IterationInfo{info_.iterations, error, true, clock.seconds()})) {
      info_.status = Status::Stopped;
      return false;
    }
    return true;
  }
};

}  // namespace fcsolve
