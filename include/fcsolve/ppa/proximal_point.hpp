// The proximal point method on FC/II(W, q, mu) (Rockafellar 1976; Acary,
// Bremond & Huber 2018, sec. on the proximal point method, Siconos' PROX):
//   r_{k+1} solves FC/II(W + alpha_k I, q - alpha_k r_k, mu),
// i.e. the contact law with u + alpha_k (r - r_k) in place of u. The
// regularised W is positive definite on rank-deficient W (many contacts on
// few bodies), where plain Newton's Jacobian is singular. Each subproblem
// is solved by an inner FC/II solver (the Inner policy: semismooth Newton by
// default, NSGS as an alternative) warm-started from r_k.
//
// alpha_k = clamp(f_k sigma err_k^nu, alpha_min, alpha_max) * mean|W_ii|, with
// err_k the FCLIB error of r_k and f_k a factor multiplied by 10 after a
// failed inner solve and divided by 10 after one that succeeds in a few
// iterations (the rules of Siconos' PROX, ibid.); the inner tolerance is
// max(err_k / 10, tol / nc) in the outer problem's units. A failed inner
// solve is still taken when it lowered the error; otherwise r_k is kept and
// retried with the larger alpha (a better-conditioned subproblem). Alpha
// stuck at alpha_max with no step taken is a stall.
//
// Success is declared only on the FCLIB error of r (problem/error.hpp) of the
// original problem. The inner solver's compute() runs once per outer
// iteration (its cached diagonal blocks, rho and scale depend on alpha and
// q). The subproblems share one pattern, so the Newton inner rereads the
// values only (newton_solver.hpp: no new Jacobian pattern, no new symbolic
// analysis); the inner iterations allocate nothing.
#pragma once

#include <fcsolve/cone/cones.hpp>
#include <fcsolve/core/exceptions.hpp>
#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/core/solver_settings.hpp>
#include <fcsolve/core/timer.hpp>
#include <fcsolve/formulation/alart_curnier.hpp>
#include <fcsolve/newton/newton_solver.hpp>
#include <fcsolve/ppa/proximal_point_settings.hpp>
#include <fcsolve/ppa/proximal_problem.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/problem/validate.hpp>
#include <fcsolve/storage/storage.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

namespace fcsolve {

template <class Cone, class Inner = Newton<AlartCurnierFunction, Cone, SparseStorage<Cone::dim>>>
class ProximalPoint {
  static_assert(is_cone_v<Cone>, "Cone must be a cone policy (cone/cones.hpp)");
  static_assert(Inner::d == Cone::dim, "the inner solver must be built for the same cone");

 public:
  static constexpr int d = Cone::dim;
  using InnerSolver = Inner;
  using Settings = ProximalPointSettings<typename Inner::Settings>;

  explicit ProximalPoint(const Settings& s = {}) : settings_(s) {}

  Settings& settings() { return settings_; }
  const Settings& settings() const { return settings_; }
  const SolverInfo& info() const { return info_; }
  /// The inner solver (its info() is that of the last subproblem).
  const Inner& inner() const { return inner_; }

  /// Validates p and copies W into the regularised storage. The viewed data
  /// must outlive the solver.
  ProximalPoint& compute(const LocalProblemView& p) {
    Stopwatch clock;
    problem_.emplace(validated(p, d));
    error_.emplace(p);
    proximal_.compute(p);
    const Index m = p.size();
    r_.resize(m);
    trial_.resize(m);
    u_.resize(m);
    best_.resize(m);
    info_ = SolverInfo();
    info_.setup_seconds = clock.seconds();
    return *this;
  }

  /// r: warm start in, solution out (the best iterate if the solve fails);
  /// u = W r + q on return.
  const SolverInfo& solve(Eigen::Ref<Vector> r, Eigen::Ref<Vector> u) {
    const Index m = problem_ ? problem_->size() : 0;
    fcsolve::check_solve_arguments("ProximalPoint", problem_.has_value(), r, m, u, m, "u");
    check_settings();
    Stopwatch clock;
    const double setup = info_.setup_seconds;
    info_ = SolverInfo();
    info_.setup_seconds = setup;
    r_ = r;
    double error = (*error_)(r_);
    best_ = r_;
    best_error_ = error;
    const Status status = iterate(error, clock);
    if (status != Status::Converged) r_ = best_;
    r = r_;
    u.noalias() = problem_->W * r_;
    u += problem_->q;
    info_.status = status;
    info_.error = status == Status::Converged ? error : best_error_;
    char alpha[32];
    std::snprintf(alpha, sizeof alpha, "%.3g", proximal_.alpha());
    info_.message = std::to_string(inner_iterations_) + " inner iterations in " +
                    std::to_string(info_.iterations) + " subproblems (" +
                    std::to_string(inner_failures_) + " failed), last alpha " + alpha;
    info_.solve_seconds = clock.seconds();
    return info_;
  }

 private:
  Status iterate(double& error, const Stopwatch& clock) {
    const Settings& s = settings_;
    inner_iterations_ = inner_failures_ = 0;
    const double unit = proximal_.diagonal_scale();
    const double nc = double(std::max<Index>(problem_->num_contacts(), 1));
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
      proximal_.set_alpha(alpha * unit);
      FCSOLVE_NO_MALLOC_BEGIN();
      proximal_.set_centre(r_);
      FCSOLVE_NO_MALLOC_END();

      // inner tolerance max(err_k / 10, tol / nc) on the outer scale ||q||,
      // rewritten on the subproblem's own scale ||q - alpha r_k||
      const LocalProblemView& sub = proximal_.view();
      typename Inner::Settings& is = inner_.settings();
      is = s.inner;
      is.tol = std::max(error / 10, s.tol / nc) * error_->scale() / error_scale(sub.q.norm());
      is.max_iter = s.inner_max_iter;
      is.max_time = remaining;
      is.record_history = false;
      is.callback = nullptr;
      inner_.compute(sub);
      trial_ = r_;
      const SolverInfo& in = inner_.solve(trial_, u_);
      inner_iterations_ += in.iterations;

      FCSOLVE_NO_MALLOC_BEGIN();
      const double trial_error = (*error_)(trial_);
      const bool solved = in.converged();
      const bool taken = (solved && std::isfinite(trial_error)) || trial_error < error;
      if (taken) {
        r_ = trial_;
        error = trial_error;
        if (error < best_error_) {
          best_error_ = error;
          best_ = r_;
        }
      }
      FCSOLVE_NO_MALLOC_END();
      if (!solved) {
        ++inner_failures_;
        factor *= 10;
      } else if (in.iterations <= s.fast_inner_iterations) {
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

  Settings settings_;
  SolverInfo info_;
  std::optional<LocalProblemView> problem_;
  std::optional<LocalErrorEvaluator<Cone>> error_;
  ProximalProblem proximal_;
  Inner inner_;
  Vector r_, trial_, u_, best_;
  double best_error_ = 0;
  long long inner_iterations_ = 0, inner_failures_ = 0;
};

}  // namespace fcsolve
