// The outer loop of the proximal point method (Rockafellar 1976; Acary,
// Bremond & Huber 2018, sec. on the proximal point method, Siconos' PROX),
// shared by the reduced (proximal_point.hpp) and the global
// (proximal_point_global.hpp) forms: r_{k+1} solves the contact law with
// u + alpha_k (r - r_k) in place of u, by an inner solver warm-started from
// r_k.
//
// alpha_k = clamp(f_k sigma err_k^nu, alpha_min, alpha_max) * unit, with
// err_k the FCLIB error of r_k, unit the form's mean diagonal of W (or its
// estimate) and f_k a factor multiplied by 10 after a failed inner solve and
// divided by 10 after one that succeeds in a few iterations (the rules of
// Siconos' PROX, ibid.), but only when that fast success also lowered the
// outer error; the inner tolerance is max(err_k / 10, tol / nc) in
// the outer problem's units; an inner Newton that stalls (settings'
// inner_stall_window) fails early. A failed inner solve is still taken when it
// lowered the error; otherwise r_k is kept and retried with the larger alpha
// (a better-conditioned subproblem). Alpha stuck at alpha_max with no step
// taken is a stall. Success is declared only on the FCLIB error of the
// original problem.
//
// CRTP: Derived provides
//   double alpha_unit()                   alpha's unit (mean |W_ii| or its estimate)
//   double outer_scale()                  the outer problem's error scale ||q||
//   Index num_contacts()
//   double pose_subproblem(double alpha)  set up the subproblem about r_k with
//                                         this alpha (inner settings already
//                                         set); returns its own error scale
//   const SolverInfo& solve_subproblem()  inner solve from r_k into the trial
//   double trial_error()                  outer FCLIB error of the trial
//   void take_trial(), save_best()        the trial becomes r_k; r_k the best
// and the hooks between FCSOLVE_NO_MALLOC_BEGIN/END allocate nothing.
#pragma once

#include <fcsolve/core/exceptions.hpp>
#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/core/solver_settings.hpp>
#include <fcsolve/core/timer.hpp>
#include <fcsolve/ppa/proximal_point_settings.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace fcsolve {

template <class Derived, class Inner>
class ProximalPointLoop {
 public:
  static constexpr int d = Inner::d;
  using InnerSolver = Inner;
  using Settings = ProximalPointSettings<typename Inner::Settings>;

  Settings& settings() { return settings_; }
  const Settings& settings() const { return settings_; }
  const SolverInfo& info() const { return info_; }
  /// The inner solver (its info() is that of the last subproblem).
  const Inner& inner() const { return inner_; }

 protected:
  explicit ProximalPointLoop(const Settings& s) : settings_(s) {}

  /// Checks the settings, then runs the loop from the derived class's r_k
  /// whose error is `error`; on return info() is filled but for the
  /// solve's seconds, and `error` is the error of the last iterate.
  Status run(double& error, const Stopwatch& clock) {
    check_settings();
    const double setup = info_.setup_seconds;
    info_ = SolverInfo();
    info_.setup_seconds = setup;
    best_error_ = error;
    const Status status = iterate(error, clock);
    info_.status = status;
    info_.error = status == Status::Converged ? error : best_error_;
    char alpha[32];
    std::snprintf(alpha, sizeof alpha, "%.3g", alpha_);
    info_.message = std::to_string(inner_iterations_) + " inner iterations in " +
                    std::to_string(info_.iterations) + " subproblems (" +
                    std::to_string(inner_failures_) + " failed), last alpha " + alpha;
    return status;
  }

  Settings settings_;
  SolverInfo info_;
  Inner inner_;

 private:
  Status iterate(double& error, const Stopwatch& clock) {
    Derived& self = static_cast<Derived&>(*this);
    const Settings& s = settings_;
    inner_iterations_ = inner_failures_ = 0;
    const double unit = self.alpha_unit();
    const double nc = double(std::max<Index>(self.num_contacts(), 1));
    double factor = 1;  // the failure / fast-success rule on alpha
    while (true) {
      if (!std::isfinite(error)) return Status::NumericalError;
      if (error <= s.tol) return Status::Converged;
      if (info_.iterations >= s.max_iter) return Status::MaxIterations;
      const double remaining = s.max_time - clock.seconds();
      if (!(remaining > 0)) return Status::TimeLimit;
      ++info_.iterations;

      // alpha_k = f_k sigma err_k^nu, bounded; the factor follows the bound so
      // that it cannot run away (Acary, Bremond & Huber 2018, PROX).
      const double base = s.sigma * std::pow(error, s.nu);
      const double alpha = std::clamp(factor * base, s.alpha_min, s.alpha_max);
      if (base > 0) factor = alpha / base;
      alpha_ = alpha * unit;

      typename Inner::Settings& is = inner_.settings();
      is = s.inner;
      is.max_iter = s.inner_max_iter;
      if constexpr (has_stall_window<typename Inner::Settings>::value)
        if (s.inner_stall_window > 0) is.stall_window = s.inner_stall_window;
      is.max_time = remaining;
      is.record_history = false;
      is.callback = nullptr;
      // inner tolerance max(err_k / 10, tol / nc) on the outer scale ||q||,
      // rewritten on the subproblem's own scale (||q - alpha r_k||)
      const double sub_scale = self.pose_subproblem(alpha_);
      is.tol = std::max(error / 10, s.tol / nc) * self.outer_scale() / sub_scale;
      const SolverInfo& in = self.solve_subproblem();
      inner_iterations_ += in.iterations;

      const double error_before = error;
      FCSOLVE_NO_MALLOC_BEGIN();
      const double trial_error = self.trial_error();
      const bool solved = in.converged();
      const bool taken = (solved && std::isfinite(trial_error)) || trial_error < error;
      if (taken) {
        self.take_trial();
        error = trial_error;
        if (error < best_error_) {
          best_error_ = error;
          self.save_best();
        }
      }
      FCSOLVE_NO_MALLOC_END();
      // the inner solve was given the whole remaining budget: it is spent
      if (in.status == Status::TimeLimit) return error <= s.tol ? Status::Converged : Status::TimeLimit;
      if (!solved) {
        ++inner_failures_;
        factor *= 10;
      } else if (in.iterations <= s.fast_inner_iterations && error < error_before) {
        // Coulomb friction is not monotone: a subproblem solved fast can still
        // raise the outer error. Lowering alpha then made the loop cycle
        // between a small alpha (fast, error up) and a larger one (inner
        // Newton stalls, error down): a generated sphere pile of 1000 contacts
        // sat at 3e-5 for 20 s. Alpha is lowered only on progress.
        factor /= 10;
      }

      if (s.record_history) info_.history.push_back(error);
      if (callback_requests_stop(s.callback,
                                 IterationInfo{info_.iterations, error, true, clock.seconds()}))
        return error <= s.tol ? Status::Converged : Status::Stopped;
      if (!taken && alpha >= s.alpha_max && error > s.tol) return Status::Stalled;
    }
  }

  void check_settings() const {
    const Settings& s = settings_;
    if (!(s.sigma > 0) || !(s.nu >= 0) || !(s.alpha_min > 0) || !(s.alpha_max >= s.alpha_min))
      throw UsageError("ppa: needs sigma > 0, nu >= 0 and 0 < alpha_min <= alpha_max");
  }

  double best_error_ = 0, alpha_ = 0;
  long long inner_iterations_ = 0, inner_failures_ = 0;
};

}  // namespace fcsolve
