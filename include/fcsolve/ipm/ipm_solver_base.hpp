// What the three interior-point solvers (SocqpIpm, AclmSolver,
// NonsmoothIpm) share: settings, the form and its engine, validation, the
// conversion of an iterate to (r, v) or (r, u), the natural-map polish, and
// the translation of engine exits into a Status and a message.
#pragma once

#include <fcsolve/core/exceptions.hpp>
#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/core/solver_settings.hpp>
#include <fcsolve/core/timer.hpp>
#include <fcsolve/ipm/interior_point.hpp>
#include <fcsolve/ipm/natural_map_polish.hpp>
#include <fcsolve/problem/validate.hpp>

#include <cstdio>
#include <limits>
#include <memory>
#include <string>

namespace fcsolve {
namespace ipm {

/// Settings of the interior-point solvers; the step knobs and their
/// defaults are IpmStepSettings' (ipm/interior_point.hpp).
struct IpmSettings : SolverSettings, IpmStepSettings {
  IpmSettings() { max_iter = 100; }
  bool polish = true;           ///< finish with Newton steps on the natural map
  int polish_iterations = 10;
  /// Switch to the polish once the error is below this and the IPM stops
  /// halving it every three iterations.
  double polish_below = 1e-5;
};

inline std::string format_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2e", x);
  return buf;
}

/// Where a solve spent its time (for benchmarks: the factorisation share).
struct IpmStatistics {
  int factorizations = 0;
  double factor_seconds = 0;  ///< assembling + factorising Newton matrices
};

template <class Form>
class IpmSolverBase {
 public:
  static constexpr int D = Form::dim;
  using Cone = typename Form::Cone;

  const SolverInfo& info() const { return info_; }
  const IpmStatistics& statistics() const { return stats_; }
  const Form& form() const { return *form_; }
  /// The engine's current iterate as (r, w), w = v (global form) or u (local
  /// form): for a callback that inspects the path while the solve runs.
  void current_point(Vector& r, Vector& w) const { extract(it_, r, w); }

 protected:
  /// Validates the problem, checks what the IPM supports, builds the form.
  template <class View>
  void compute_form(const View& p) {
    Stopwatch clock;
    validate(p);
    if (p.d != D)
      throw UsageError("interior-point solver compiled for d = " + std::to_string(D) +
                       ", problem has d = " + std::to_string(p.d));
    if constexpr (Form::is_global)
      if (p.has_bilateral())
        throw UsageError("the global interior-point form has no bilateral constraints (G, b): "
                         "solve the reduced problem instead");
    form_ = std::make_unique<Form>();
    form_->compute(p);
    engine_ = std::make_unique<InteriorPoint<Form>>(*form_);
    it_.resize(form_->primal_size(), form_->size(), form_->num_contacts());
    info_ = SolverInfo();
    info_.setup_seconds = clock.seconds();
  }

  void require_computed() const {
    if (!form_) throw UsageError("interior-point solver: call compute(problem) before solve()");
  }

  /// Checks solve()'s arguments (compute() called; r, the warm start: m
  /// finite entries; w: n entries for v, m for u) and resets info() (keeping
  /// the setup time) and the best point.
  SolverInfo& begin_solve(const Eigen::Ref<Vector>& r, const Eigen::Ref<Vector>& w) {
    require_computed();
    const Index m = form_->size(), n = Form::is_global ? form_->primal_size() : m;
    fcsolve::check_solve_arguments("interior-point solver", true, r, m, w, n, Form::is_global ? "v" : "u");
    stats_ = IpmStatistics();
    const double setup = info_.setup_seconds;
    info_ = SolverInfo();
    info_.setup_seconds = setup;
    best_ = BestPoint();
    return info_;
  }

  /// How solve() uses its warm start r (an interior point starts from the
  /// centre of the cones, not from a given point): a warm start that meets
  /// tol is the answer, with no iteration; a nonzero one whose error is
  /// below polish_below is finished by the natural-map polish; otherwise the
  /// IPM starts cold. Either way the warm start (or its polished point) is
  /// the first best point, so solve() never returns a worse one. `frozen`:
  /// the s of the convex problem (null: Coulomb's law). True when the best
  /// point meets tol: solve() is done.
  bool try_warm_start(const Eigen::Ref<const Vector>& r, const IpmSettings& st,
                      const Vector* frozen, double seconds_left) {
    Vector r0 = r, w0;
    const double error = form_->error_of(r0, w0, frozen ? *frozen : it_.s, frozen != nullptr);
    consider(r0, w0, error);
    if (error <= st.tol) {
      info_.message = "the warm start meets tol";
      return true;
    }
    if (!st.polish || !(error <= st.polish_below) || (r0.array() == 0).all()) return false;
    const PolishResult pr = polish(st, r0, w0, frozen, st.tol, seconds_left);
    info_.message = "warm start: " + describe_polish(pr);
    consider(r0, w0, pr.error);
    return best_.error <= st.tol;
  }

  /// Appends a part to info().message ("; " between parts).
  void add_to_message(const std::string& text) {
    info_.message += (info_.message.empty() ? "" : "; ") + text;
  }

  /// Keeps (r, w) when its error (of the problem solved) beats the best
  /// point so far; true when it did.
  bool consider(const Vector& r, const Vector& w, double error) {
    if (!(error < best_.error) && best_.r.size()) return false;
    best_.r = r;
    best_.w = w;
    best_.error = error;
    return true;
  }

  /// Writes the best point into (r, w) and its error into info(); the status
  /// is Converged iff that error is <= tol ("converged; " then leads the
  /// message), `otherwise` if not.
  const SolverInfo& finish(Eigen::Ref<Vector> r, Eigen::Ref<Vector> w, double tol,
                           Status otherwise, const Stopwatch& clock) {
    r = best_.r;
    w = best_.w;
    info_.error = best_.error;
    info_.status = best_.error <= tol ? Status::Converged : otherwise;
    if (info_.status == Status::Converged) info_.message = "converged; " + info_.message;
    info_.solve_seconds = clock.seconds();
    return info_;
  }

  /// One engine run as these settings ask for it: the step knobs, the
  /// callback, the history, the switch to the polish; tol and the budgets
  /// are the caller's (what is left of them).
  EngineRun engine_run(const IpmSettings& s, bool coupled, double tol, int max_iter,
                       double max_time) const {
    EngineRun o;
    o.step = s;
    o.tol = tol;
    o.max_iter = max_iter;
    o.max_time = max_time;
    o.record_history = s.record_history;
    o.callback = &s.callback;
    o.coupled = coupled;
    o.slow_below = s.polish ? s.polish_below : 0.0;
    return o;
  }

  /// r and v (global) or u = W r + q (local) of the iterate.
  void extract(const Iterate& it, Vector& r, Vector& w) const {
    form_->reaction(it, r);
    if constexpr (Form::is_global) w = it.v;
    else form_->velocity(it, w);
  }

  /// Newton on the natural map from (r, w); w is v (global) or u (local,
  /// recomputed). `frozen`: the s of the convex problem, null for Coulomb.
  /// No step starts after `seconds_left` (the rest of the solve's max_time).
  PolishResult polish(const IpmSettings& s, Vector& r, Vector& w, const Vector* frozen,
                      double target, double seconds_left) {
    using Backend = typename Form::Backend;
    if constexpr (Form::is_global) {
      return polish_global<D, Backend>(form_->view(), form_->error_scale(), w, r, frozen, target,
                                       s.polish_iterations, seconds_left);
    } else {
      PolishResult res = polish_local<D, Backend>(form_->view(), r, frozen, target,
                                                  s.polish_iterations, seconds_left);
      w = form_->view().W * r + form_->view().q;
      return res;
    }
  }

  /// The local velocity u of a solve's second vector: u = H^T v + w (the
  /// problem's w) for the global form, u itself for the local one.
  Vector velocity_of(const Vector& v_or_u) const {
    if constexpr (Form::is_global) {
      Vector u = form_->view().H.transpose() * v_or_u;
      u += form_->view().w;
      return u;
    } else {
      return v_or_u;
    }
  }

  /// The FCLIB error of (r, w) (core/error.hpp), w = v (global) or u (local).
  double fclib_error(const Vector& r, const Vector& w) const {
    if constexpr (Form::is_global)
      return global_error_report(form_->view(), form_->error_scale(), r, w).error;
    else
      return local_error_report(form_->view(), r).error;
  }

  static Status status_of(IpmExit e) {
    switch (e) {
      case IpmExit::Converged: return Status::Converged;
      case IpmExit::MaxIterations: return Status::MaxIterations;
      case IpmExit::TimeLimit: return Status::TimeLimit;
      case IpmExit::NumericalError: return Status::NumericalError;
      case IpmExit::Stopped: return Status::Stopped;
      default: return Status::Stalled;
    }
  }

  /// "IPM: 12 iterations (slow progress), error 3.1e-09" (+ the engine note
  /// and a fake-solution warning when the talk's test was met too early).
  static std::string describe(const char* what, const IpmReport& rep) {
    std::string m = std::string(what) + ": " + std::to_string(rep.iterations) + " iterations (" +
                    to_string(rep.exit) + "), error " + format_number(rep.error);
    if (!rep.note.empty()) m += " [" + rep.note + "]";
    if (rep.fake_iteration >= 0)
      m += "; the published stopping test held at iteration " + std::to_string(rep.fake_iteration) +
           " with error " + format_number(rep.fake_error) + " (a fake solution, not accepted)";
    return m;
  }
  static std::string describe_polish(const PolishResult& p) {
    return "Newton polish: " + std::to_string(p.iterations) + " steps, error " +
           format_number(p.initial_error) + " -> " + format_number(p.error);
  }

  /// Runs the engine and accounts for its factorisations.
  IpmReport run_engine(Iterate& it, const EngineRun& opt) {
    IpmReport rep = engine_->run(it, opt);
    stats_.factorizations += rep.factorizations;
    stats_.factor_seconds += rep.factor_seconds;
    return rep;
  }

  /// The best (r, w) of a solve and its error: w = v (global) or u (local).
  struct BestPoint {
    Vector r, w;
    double error = std::numeric_limits<double>::infinity();
  };

  std::unique_ptr<Form> form_;
  std::unique_ptr<InteriorPoint<Form>> engine_;
  Iterate it_;
  SolverInfo info_;
  IpmStatistics stats_;
  BestPoint best_;
};

}  // namespace ipm
}  // namespace fcsolve
