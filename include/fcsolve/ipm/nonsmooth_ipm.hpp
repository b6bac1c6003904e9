// The nonsmooth interior-point method (NIPM) for the full FC/I (reference
// talk, "Nonsmooth Interior-Point Method"; H.M. Nguyen & P. Armand): the
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
};

/// The recovery strategies (steps 2-4 above) and the order they are tried in.
enum class Recovery { Resume, Recentre, Aclm };
inline constexpr Recovery kRecoveryOrder[] = {Recovery::Resume, Recovery::Recentre, Recovery::Aclm};

/// What a recovery strategy did: NotApplicable (its precondition failed,
/// nothing ran), Ran, or Stopped (the callback asked to stop).
enum class RecoveryResult { NotApplicable, Ran, Stopped };

template <class Form>
class NonsmoothIpm : public IpmSolverBase<Form> {
  static constexpr int N = Form::dim;

 public:
  using Settings = NipmSettings;
  explicit NonsmoothIpm(const NipmSettings& settings = NipmSettings()) : settings_(settings) {}
  NipmSettings& settings() { return settings_; }
  const NipmSettings& settings() const { return settings_; }

  template <class View>
  NonsmoothIpm& compute(const View& p) {
    this->compute_form(p);
    return *this;
  }

  /// r, and w = v (global form) or u (local form).
  SolverInfo solve(Vector& r, Vector& w) {
    Stopwatch clock;
    SolverInfo& info = this->begin_solve();
    const NipmSettings& st = settings_;
    Iterate& it = this->it_;
    it.s.setZero(this->form_->num_contacts());
    this->engine_->cold_start(it, true);

    best_error_ = std::numeric_limits<double>::infinity();
    best_r_.resize(0);
    std::string& msg = info.message;
    int total = 0;
    auto remaining = [&] { return st.max_iter - total; };
    auto run = [&](const char* what, IpmOptions opt) {
      opt.max_iter = remaining();
      opt.max_time = st.max_time - clock.seconds();
      opt.iteration_offset = total;
      opt.seconds_offset = clock.seconds();
      const IpmReport rep = this->run_engine(it, opt);
      total += rep.iterations;
      info.history.insert(info.history.end(), rep.history.begin(), rep.history.end());
      msg += (msg.empty() ? "" : "; ") + this->describe(what, rep);
      Vector rr, ww;
      this->extract(it, rr, ww);
      consider(rr, ww, rep.error);
      last_exit_ = rep.exit;
      return rep;
    };
    auto polish_best = [&] {
      if (!st.polish || best_error_ <= st.tol) return;
      Vector rr = best_r_, ww = best_w_;
      const PolishResult pr = this->polish(st, rr, ww, nullptr, st.tol,
          st.max_time - clock.seconds());
      msg += "; " + this->describe_polish(pr);
      consider(rr, ww, pr.error);
    };
    auto done = [&] { return best_error_ <= st.tol || remaining() <= 0 || clock.seconds() > st.max_time; };

    // 1. NIPM until it slows down, then the polish.
    IpmOptions opt = this->engine_options(st, true, st.tol, st.max_iter, st.max_time);
    const IpmReport first = run("NIPM", opt);
    polish_best();
    bool stopped = first.exit == IpmExit::Stopped;

    // 2-4. The recovery strategies, in order, while tol is not met.
    auto recover = [&](Recovery step) -> RecoveryResult {
      switch (step) {
        case Recovery::Resume: {  // the IPM resumed while it still progresses
          if (first.exit != IpmExit::SlowProgress) return RecoveryResult::NotApplicable;
          IpmOptions resumed = opt;
          resumed.slow_below = 0;
          const IpmReport rep = run("NIPM resumed", resumed);
          polish_best();
          return rep.exit == IpmExit::Stopped ? RecoveryResult::Stopped : RecoveryResult::Ran;
        }
        case Recovery::Recentre: {  // from the best iterate at a larger barrier parameter
          if (!st.recentre || best_iterate_.x.size() == 0) return RecoveryResult::NotApplicable;
          it = best_iterate_;
          recentre(it, 1e4);
          IpmOptions safe = opt;
          safe.sigma_max = std::min(st.sigma_max, 0.3);
          safe.step_fraction = std::min(st.step_fraction, 0.9);
          safe.slow_below = st.polish ? st.polish_below : 0.0;
          const IpmReport rep = run("re-centred NIPM", safe);
          polish_best();
          return rep.exit == IpmExit::Stopped ? RecoveryResult::Stopped : RecoveryResult::Ran;
        }
        case Recovery::Aclm: {  // ACLM Newton from the best iterate's s = ||u_T||
          AclmSettings as;
          static_cast<IpmSettings&>(as) = static_cast<const IpmSettings&>(st);
          as.sigma_max = 1.0;
          as.max_iter = remaining();
          as.max_time = st.max_time - clock.seconds();
          as.record_history = false;
          as.callback = IterationCallback();
          AclmSolver<Form> aclm(as);
          aclm.compute(this->form_->view());
          aclm.set_initial_s(tangential_speeds(best_r_, best_w_));
          Vector rr, ww;
          const SolverInfo ai = aclm.solve(rr, ww);
          total += ai.iterations;
          this->stats_.factorizations += aclm.statistics().factorizations;
          this->stats_.factor_seconds += aclm.statistics().factor_seconds;
          msg += "; fallback " + aclm.summary();
          consider(rr, ww, ai.error);
          return RecoveryResult::Ran;
        }
      }
      return RecoveryResult::NotApplicable;
    };
    for (const Recovery step : kRecoveryOrder) {
      if (done() || stopped || !st.recover) break;
      stopped = recover(step) == RecoveryResult::Stopped;
    }
    r = best_r_;
    w = best_w_;
    info.iterations = total;
    info.error = best_error_;
    if (best_error_ <= st.tol) {
      info.status = Status::Converged;
      msg = "converged; " + msg;
    } else if (stopped) {
      info.status = Status::Stopped;
    } else if (remaining() <= 0) {
      info.status = Status::MaxIterations;
    } else if (clock.seconds() > st.max_time) {
      info.status = Status::TimeLimit;
    } else {
      info.status = last_exit_ == IpmExit::NumericalError ? Status::NumericalError : Status::Stalled;
    }
    info.solve_seconds = clock.seconds();
    return info;
  }

 private:
  /// Keeps (r, w) if its FCLIB error beats the best so far (and the iterate
  /// behind it, for the re-centring).
  void consider(const Vector& r, const Vector& w, double error) {
    if (!(error < best_error_) && best_r_.size()) return;
    best_error_ = error;
    best_r_ = r;
    best_w_ = w;
    best_iterate_ = this->it_;
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

  /// s_a = ||u_T^a|| of (r, w) (u = H^T v + w for the global form).
  Vector tangential_speeds(const Vector& r, const Vector& w) const {
    Vector u;
    if constexpr (Form::is_global) u = this->form_->view().H.transpose() * w + this->form_->view().w;
    else u = w;
    (void)r;
    Vector s(this->form_->num_contacts());
    for (Index a = 0; a < s.size(); ++a) s[a] = u.template segment<N - 1>(a * N + 1).norm();
    return s;
  }

  NipmSettings settings_;
  double best_error_ = 0;
  Vector best_r_, best_w_;
  Iterate best_iterate_;
  IpmExit last_exit_ = IpmExit::MaxIterations;
};

template <int N = 3, class Factorization = SparseKktFactorization<DefaultBackend>>
using GlobalNipm = NonsmoothIpm<GlobalForm<N, Factorization>>;
template <int N = 3, class Factorization = SparseKktFactorization<DefaultBackend>>
using LocalNipm = NonsmoothIpm<LocalForm<N, Factorization>>;

}  // namespace ipm
}  // namespace fcsolve
