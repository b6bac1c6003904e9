// The nonsmooth interior-point method (NIPM) for the full FC/I (Nguyen &
// Armand, in Acary 2025 (talk), "Nonsmooth Interior-Point Method", eq. (23);
// docs/references.md): the
// unknowns (v, u~, r, s) with
//   M v - H r - f = 0,  H^T v + w + A s - u~ = 0,  s - ||u~_T|| = 0,
//   u~ o r = 2 tau e,   (u~, r) in K* x K,
// followed by Newton with the Jacobian block L = (0, d||u~_T||^T) (the zero
// subgradient at u~_T = 0) and Mehrotra's centring with sigma <= sigma_max
// (ipm/interior_point.hpp, `coupled`). Success is decided by the FCLIB error
// alone; the talk's stopping test max(||H^T v + w - u~||, ||M v + f - H r||,
// |s - ||u~_T|| |, ||u~ o r||) <= tol is only watched, and reported when it
// would have accepted a "fake solution".
//
// Where the published NIPM fails (iterates stuck at the boundary, a central
// path that turns back), this one recovers, in this order, each step only if
// the previous did not reach tol:
//  1. Newton polish on the natural map from the best iterate, as soon as the
//     IPM slows down below polish_below;
//  2. the IPM resumed until it stalls, then the polish again;
//  3. re-centring: the best iterate pushed back into the interior at a
//     barrier parameter 1e4 x larger (a restart of the path following from a
//     point closer to the central path), with a more conservative
//     sigma_max and step, then the polish;
//  4. the ACLM Newton loop warm-started from the best iterate's
//     s = ||u_T|| (a sequence of convex problems, which an IPM solves
//     reliably), then the polish.
// info().message lists what was done.
#pragma once

#include <fcsolve/ipm/aclm.hpp>

namespace fcsolve {
namespace ipm {

struct NipmSettings : IpmSettings {
  NipmSettings() {
    max_iter = 200;
    sigma_max = 0.5;  // the talk's sigma in (0, 0.5)
  }
  bool recover = true;   ///< run the recovery steps 2-4 when step 1 fails
  bool recentre = true;  ///< include step 3 (re-centring) in the recovery
  /// A soft time limit in seconds (0: none; EngineRun::soft_time): the solve
  /// keeps to it (the polishes and recovery steps included) unless the path
  /// following went on past it, its rate predicting tol; then to max_time.
  double soft_time = 0;
};

/// The recovery strategies (steps 2-4 above) and the order they are tried in.
enum class Recovery { Resume, Recentre, Aclm };
inline constexpr Recovery kRecoveryOrder[] = {Recovery::Resume, Recovery::Recentre, Recovery::Aclm};

/// What a recovery strategy did: NotApplicable (its precondition failed,
/// nothing ran), Ran, or Stopped (the callback asked to stop).
enum class RecoveryResult { NotApplicable, Ran, Stopped };

template <class Form>
class NonsmoothIpm : public IpmSolverBase<Form> {
  static constexpr int D = Form::dim;

 public:
  using Settings = NipmSettings;
  explicit NonsmoothIpm(const NipmSettings& settings = NipmSettings()) : settings_(settings) {}
  NipmSettings& settings() { return settings_; }
  const NipmSettings& settings() const { return settings_; }

  /// Validates the problem, builds the form (KKT pattern, scaling).
  NonsmoothIpm& compute(const typename Form::View& p) {
    this->compute_form(p);
    return *this;
  }

  /// From the warm start r (ipm_solver_base.hpp, try_warm_start): r, and
  /// w = v (global form) or u (local form).
  const SolverInfo& solve(Eigen::Ref<Vector> r, Eigen::Ref<Vector> w) {
    Stopwatch clock;
    this->begin_solve(r, w);
    const NipmSettings& st = settings_;
    best_iterate_ = Iterate();
    total_ = 0;
    stopped_ = false;
    factorization_refused_ = false;
    last_exit_ = IpmExit::Converged;
    limit_ = st.soft_time > 0 ? std::min(st.soft_time, st.max_time) : st.max_time;
    if (!this->try_warm_start(r, st, nullptr, limit_)) {
      // 1. NIPM until it slows down, then the polish.
      Iterate& it = this->it_;
      it.s.setZero(this->form_->num_contacts());
      this->engine_->cold_start(it, true, st.max_time - clock.seconds());
      EngineRun opt = this->engine_run(st, true, st.tol, st.max_iter, st.max_time);
      opt.soft_time = st.soft_time;
      first_exit_ = run("NIPM", opt, clock).exit;
      polish_best(clock);
      stopped_ = first_exit_ == IpmExit::Stopped;
      // 2-4. The recovery strategies, in order, while tol is not met.
      for (const Recovery step : kRecoveryOrder) {
        if (done(clock) || stopped_ || !st.recover) break;
        stopped_ = recover(step, opt, clock) == RecoveryResult::Stopped;
      }
    }
    this->info_.iterations = total_;
    Status otherwise = Status::Stalled;
    if (stopped_) otherwise = Status::Stopped;
    else if (remaining() <= 0) otherwise = Status::MaxIterations;
    else if (clock.seconds() > limit_ || factorization_refused_) otherwise = Status::TimeLimit;
    else if (last_exit_ == IpmExit::NumericalError) otherwise = Status::NumericalError;
    return this->finish(r, w, st.tol, otherwise, clock);
  }

 private:
  int remaining() const { return settings_.max_iter - total_; }
  bool done(const Stopwatch& clock) const {
    return this->best_.error <= settings_.tol || remaining() <= 0 || clock.seconds() > limit_ ||
           factorization_refused_;
  }
  /// The time this solve keeps to: soft_time, or max_time once a run went
  /// on past soft_time.
  double limit_ = 0;

  /// One engine run from the current iterate with what is left of the
  /// iteration and time budgets; its point is a candidate.
  IpmReport run(const char* what, EngineRun opt, const Stopwatch& clock) {
    opt.max_iter = remaining();
    opt.max_time = settings_.max_time - clock.seconds();
    opt.iteration_offset = total_;
    opt.seconds_offset = clock.seconds();
    const IpmReport rep = this->run_engine(this->it_, opt);
    if (rep.past_soft_time) {
      limit_ = settings_.max_time;
      this->add_to_message(kPastSoftTimeNote);
    }
    total_ += rep.iterations;
    SolverInfo& info = this->info_;
    info.history.insert(info.history.end(), rep.history.begin(), rep.history.end());
    this->add_to_message(this->describe(what, rep));
    Vector rr, ww;
    this->extract(this->it_, rr, ww);
    consider_iterate(rr, ww, rep.error);
    last_exit_ = rep.exit;
    factorization_refused_ = factorization_refused_ || rep.factorization_refused;
    return rep;
  }

  /// The natural-map polish from the best point, unless it meets tol.
  void polish_best(const Stopwatch& clock) {
    const NipmSettings& st = settings_;
    // (its Newton matrices are of the same problem: where the IPM's would
    // not fit in the time left, neither would they)
    if (!st.polish || this->best_.error <= st.tol || factorization_refused_) return;
    Vector rr = this->best_.r, ww = this->best_.w;
    const PolishResult pr = this->polish(st, rr, ww, nullptr, st.tol, limit_ - clock.seconds());
    this->add_to_message(this->describe_polish(pr));
    this->consider(rr, ww, pr.error);
  }

  /// Runs one recovery strategy (steps 2-4 of the header comment).
  RecoveryResult recover(Recovery step, const EngineRun& opt, const Stopwatch& clock) {
    const NipmSettings& st = settings_;
    switch (step) {
      case Recovery::Resume: {  // the IPM resumed while it still progresses
        if (first_exit_ != IpmExit::SlowProgress) return RecoveryResult::NotApplicable;
        EngineRun resumed = opt;
        resumed.slow_below = 0;
        const IpmReport rep = run("NIPM resumed", resumed, clock);
        polish_best(clock);
        return rep.exit == IpmExit::Stopped ? RecoveryResult::Stopped : RecoveryResult::Ran;
      }
      case Recovery::Recentre: {  // from the best iterate at a larger barrier parameter
        if (!st.recentre || best_iterate_.x.size() == 0) return RecoveryResult::NotApplicable;
        this->it_ = best_iterate_;
        recentre(this->it_, 1e4);
        EngineRun safe = opt;
        safe.step.sigma_max = std::min(st.sigma_max, 0.3);
        safe.step.step_fraction = std::min(st.step_fraction, 0.9);
        safe.slow_below = st.polish ? st.polish_below : 0.0;
        const IpmReport rep = run("re-centred NIPM", safe, clock);
        polish_best(clock);
        return rep.exit == IpmExit::Stopped ? RecoveryResult::Stopped : RecoveryResult::Ran;
      }
      case Recovery::Aclm: return aclm_from_best(clock);
    }
    return RecoveryResult::NotApplicable;
  }

  /// Step 4: the ACLM Newton loop from the best point's s = ||u_T||.
  RecoveryResult aclm_from_best(const Stopwatch& clock) {
    AclmSettings as;
    static_cast<IpmSettings&>(as) = static_cast<const IpmSettings&>(settings_);
    as.sigma_max = 1.0;
    as.max_iter = remaining();
    as.max_time = limit_ - clock.seconds();
    as.record_history = false;
    as.callback = IterationCallback();
    AclmSolver<Form> aclm(as);
    aclm.compute(this->form_->view());
    aclm.set_initial_s(tangential_speeds_of_best());
    Vector rr = Vector::Zero(this->best_.r.size()), ww(this->best_.w.size());
    const SolverInfo& ai = aclm.solve(rr, ww);
    total_ += ai.iterations;
    this->stats_.factorizations += aclm.statistics().factorizations;
    this->stats_.factor_seconds += aclm.statistics().factor_seconds;
    this->add_to_message("fallback " + aclm.summary());
    consider_iterate(rr, ww, ai.error);
    return RecoveryResult::Ran;
  }

  /// A candidate (r, w) and, when it is the best so far, the iterate behind
  /// it (for the re-centring).
  void consider_iterate(const Vector& r, const Vector& w, double error) {
    if (this->consider(r, w, error)) best_iterate_ = this->it_;
  }

  /// Pushes every block back into int L so that x^T y grows by ~factor.
  static void recentre(Iterate& it, double factor) {
    const double mu = std::max(it.x.dot(it.y) / double(it.s.size()), 1e-300);
    const double xs = std::max(it.x.cwiseAbs().maxCoeff(), 1e-300);
    const double ys = std::max(it.y.cwiseAbs().maxCoeff(), 1e-300);
    // shifts with shift_x * shift_y = factor * mu and the x/y balance of the point
    const double t = std::sqrt(factor * mu / (xs * ys));
    InteriorPoint<Form>::push_inside(it, t * xs, t * ys);
  }

  /// s_a = ||u_T^a|| of the best point (0 on a frictionless contact).
  Vector tangential_speeds_of_best() const {
    return tangential_speeds<D>(this->velocity_of(this->best_.w), this->form_->mu());
  }

  NipmSettings settings_;
  Iterate best_iterate_;
  int total_ = 0;
  bool stopped_ = false;
  /// a run ended before a factorisation that would not end within max_time
  bool factorization_refused_ = false;
  IpmExit first_exit_ = IpmExit::MaxIterations, last_exit_ = IpmExit::MaxIterations;
};

template <class Cone = Coulomb3D, class Factorization = SparseKktFactorization<DefaultBackend>>
using GlobalNipm = NonsmoothIpm<GlobalForm<Cone, Factorization>>;
template <class Cone = Coulomb3D, class Factorization = SparseKktFactorization<DefaultBackend>>
using LocalNipm = NonsmoothIpm<LocalForm<Cone, Factorization>>;

}  // namespace ipm
}  // namespace fcsolve
