// What the Tresca and Panagiotopoulos fixed points share: their settings,
// the adaptive tolerance of their inner solves, and the outer loop with its
// budgets, callback, best iterate and report (SplittingSolver, a base that
// a method completes with its compute() and its outer step). Both solve
// their subproblems by NSGS on the threshold sets (cone/tresca.hpp).
#pragma once

#include <fcsolve/cone/cones.hpp>
#include <fcsolve/cone/tresca.hpp>
#include <fcsolve/config.hpp>
#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/core/solver_settings.hpp>
#include <fcsolve/core/status.hpp>
#include <fcsolve/core/timer.hpp>
#include <fcsolve/core/types.hpp>
#include <fcsolve/local/projection.hpp>
#include <fcsolve/nsgs/nsgs_solver.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/problem/local_problem.hpp>
#include <fcsolve/problem/validate.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace fcsolve {

struct SplittingSettings : SolverSettings {
  /// Adaptive inner tolerance max(inner_tol_ratio * err_k, tol), err_k the
  /// FCLIB error of the outer iterate (Siconos' TFP / PFP use err_k / 10):
  /// early subproblems need not be solved to tol.
  double inner_tol_ratio = 0.1;
  int inner_max_iter = 1000;  ///< sweeps per inner solve
};

/// The inner tolerance of outer iteration k on the outer scale ||q||:
/// max(inner_tol_ratio * err_k, tol), never larger than the previous one,
/// and divided by 10 after outer iterations whose inner solves did no sweep
/// (they started converged, so the outer iterate did not move: near the
/// end, the subproblem's error can be below tol while the Coulomb error is
/// not). Reaching the floor tol * 1e-6 that way is a stall.
class InnerTolerance {
 public:
  double next(const SplittingSettings& s, double error, bool idle) {
    const double floor = s.tol * 1e-6;
    current_ = std::min(current_, std::max(s.inner_tol_ratio * error, s.tol));
    if (idle) {
      stalled_ = current_ <= floor;
      current_ = std::max(current_ / 10, floor);
    }
    return current_;
  }
  bool stalled() const { return stalled_; }

 private:
  double current_ = std::numeric_limits<double>::infinity();
  bool stalled_ = false;
};

/// The outer loop of a splitting on the cone policy Cone: the contract's
/// settings(), info() and solve() around the method's outer step.
template <class Cone>
class SplittingSolver {
  static_assert(is_cone_v<Cone>, "Cone must be a cone policy (cone/cones.hpp)");

 public:
  static constexpr int d = Cone::dim;
  using Settings = SplittingSettings;

  explicit SplittingSolver(const Settings& s) : settings_(s) {}
  Settings& settings() { return settings_; }
  const Settings& settings() const { return settings_; }
  const SolverInfo& info() const { return info_; }

 protected:
  /// compute()'s common part: validates p for this cone, keeps its view
  /// and the error evaluator of the Coulomb problem.
  void prepare(const LocalProblemView& p) {
    problem_.emplace(validated(p, d));
    error_.emplace(p);
    best_r_.resize(p.size());
    info_ = SolverInfo();
  }

  /// solve() by outer steps `sweeps = step(r, inner_tol, seconds_left,
  /// error)` (r in/out, the inner tolerance on the outer scale ||q||, the
  /// FCLIB error of r) until the FCLIB error of r
  /// is <= tol or a budget (max_iter, max_time), a non-finite error, a
  /// stall of the inner tolerance or the callback stops it. On failure r is
  /// the best outer iterate. `what`: the outer step, for the message.
  template <class Step>
  const SolverInfo& iterate(const char* solver, const char* what, Eigen::Ref<Vector> r,
                            Eigen::Ref<Vector> u, Step&& step) {
    const Index m = problem_ ? problem_->size() : 0;
    check_solve_arguments(solver, problem_.has_value(), r, m, u, m, "u");
    Stopwatch clock;
    const double setup = info_.setup_seconds;
    info_ = SolverInfo();
    info_.setup_seconds = setup;
    double error = (*error_)(r);
    best_r_ = r;
    best_error_ = error;
    long long sweeps = 0;
    bool idle = false;
    InnerTolerance inner_tol;
    const Status status = [&] {
      const Settings& s = settings_;
      while (true) {
        if (!std::isfinite(error)) return Status::NumericalError;
        if (error <= s.tol) return Status::Converged;
        if (inner_tol.stalled()) return Status::Stalled;
        if (info_.iterations >= s.max_iter) return Status::MaxIterations;
        if (!(clock.seconds() < s.max_time)) return Status::TimeLimit;
        ++info_.iterations;
        const int done = step(r, inner_tol.next(s, error, idle), s.max_time - clock.seconds(), error);
        idle = done == 0;
        sweeps += done;
        FCSOLVE_NO_MALLOC_BEGIN();
        error = (*error_)(r);
        if (error < best_error_) {
          best_error_ = error;
          best_r_ = r;
        }
        FCSOLVE_NO_MALLOC_END();
        if (s.record_history) info_.history.push_back(error);
        if (callback_requests_stop(s.callback, IterationInfo{info_.iterations, error, true, clock.seconds()}))
          return error <= s.tol ? Status::Converged : Status::Stopped;
      }
    }();
    if (status != Status::Converged) r = best_r_;
    u.noalias() = problem_->W * r;
    u += problem_->q;
    info_.status = status;
    info_.error = status == Status::Converged ? error : best_error_;
    info_.message = std::to_string(sweeps) + " inner sweeps in " + std::to_string(info_.iterations) + " " + what;
    info_.solve_seconds = clock.seconds();
    return info_;
  }

  Settings settings_;
  SolverInfo info_;
  std::optional<LocalProblemView> problem_;
  std::optional<LocalErrorEvaluator<Cone>> error_;

 private:
  Vector best_r_;
  double best_error_ = 0;
};

}  // namespace fcsolve
