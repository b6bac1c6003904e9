// The primal-dual path-following engine shared by the convex SOCQP IPM, the
// ACLM loops and the nonsmooth IPM (NIPM). It works on a Form (GlobalForm or
// LocalForm: residuals, Newton matrix, back-substitution, error) and runs
// Mehrotra's predictor-corrector (Mehrotra 1992) in the Jordan algebra of the
// Lorentz cone with Nesterov-Todd scaling (Vandenberghe 2010, sec. 4-5):
//   affine:    T^-1 dx + T dy = -lambda
//   sigma   =  min(sigma_max, (mu_aff / mu)^3)
//   combined:  T^-1 dx + T dy = lambda \ (sigma mu e - lambda o lambda - dxa~ o dya~)
//   step    =  min(1, gamma * largest step keeping x, y in L)
// With `coupled` the slack s is an unknown with s = ||x_T|| (the NIPM of the
// Acary 2025 (talk), "NIPM - linearization"; docs/references.md); otherwise s is frozen data (ACLM
// 2011, problem (13)). Every iterate's error is the one core/error.hpp
// defines (frozen-s natural map, or FCLIB when coupled): it alone decides
// convergence, so a "fake solution" (tiny complementarity, large natural-map
// error) is never reported as converged; the run also says when the talk's
// stopping test would have stopped on one.
#pragma once

#include <fcsolve/core/solver_settings.hpp>
#include <fcsolve/core/timer.hpp>
#include <fcsolve/ipm/form_common.hpp>
#include <fcsolve/ipm/soft_time.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace fcsolve {
namespace ipm {

/// The step knobs a user sets (IpmSettings, ipm_solver_base.hpp) and the
/// engine reads: declared, with their defaults, only here.
struct IpmStepSettings {
  double step_fraction = 0.99;   ///< fraction to the boundary gamma
  double sigma_max = 1.0;        ///< upper bound on Mehrotra's centring parameter
  int refinement = 2;            ///< iterative-refinement steps per linear solve
  double regularization = 0.0;   ///< static delta I, relative to the diagonal of K
  double neighbourhood = 0.0;    ///< eta: every contact keeps lambda_min(lambda)^2 >= eta mu (0: off)
};

/// One run of the engine, as a solver asks for it (IpmSolverBase::engine_run
/// fills it from the solver's settings): the step knobs, this run's budget,
/// and what the solver steers.
struct EngineRun {
  IpmStepSettings step;          ///< the user's step knobs
  double tol = 0;                ///< stop once the error is <= tol
  int max_iter = 0;              ///< Newton steps in this run
  double max_time = 0;           ///< seconds for this run
  bool record_history = false;
  const IterationCallback* callback = nullptr;  ///< the solver's, or none
  bool coupled = false;          ///< NIPM: s unknown with s = ||x_T||
  int stall_window = 12;         ///< iterations without a better error -> NoProgress
  /// Below this error, stop (SlowProgress) once three iterations have not
  /// halved it: a Newton polish finishes faster than the IPM's last steps,
  /// which double precision slows down (0: never).
  double slow_below = 0.0;
  double fake_residual = 0.0;    ///< the talk's stopping tolerance to watch (0: tol)
  int iteration_offset = 0;      ///< added to iteration numbers in callbacks
  double seconds_offset = 0;     ///< added to the callbacks' seconds (time before this run)
  /// A soft time limit, in the solve's seconds (seconds_offset + this run's
  /// clock; 0: none): past it the run ends with TimeLimit unless its rate
  /// predicts tol soon (soft_time_extends).
  double soft_time = 0;
};

enum class IpmExit {
  Converged,       ///< error <= tol
  MaxIterations,
  TimeLimit,
  SmallStep,       ///< steps shrank to nothing: iterates stuck at the boundary
  NoProgress,      ///< the best error did not improve for stall_window iterations
  SlowProgress,    ///< error below slow_below and no longer halving: time to polish
  NumericalError,  ///< NaN, or a factorisation that regularisation could not save
  Stopped,         ///< the callback asked to stop
};

/// The token of an engine exit, written like Status's (core/status.hpp):
/// the exits a Status also has read the same ("nan" included), the others
/// are hyphenated the same way.
inline const char* to_string(IpmExit e) {
  switch (e) {
    case IpmExit::Converged: return "converged";
    case IpmExit::MaxIterations: return "max-iterations";
    case IpmExit::TimeLimit: return "timeout";
    case IpmExit::SmallStep: return "small-steps";
    case IpmExit::NoProgress: return "no-progress";
    case IpmExit::SlowProgress: return "slow-progress";
    case IpmExit::NumericalError: return "nan";
    case IpmExit::Stopped: return "stopped";
  }
  return "?";
}

struct IpmReport {
  IpmExit exit = IpmExit::MaxIterations;
  int iterations = 0;          ///< Newton steps taken
  double error = 0;            ///< error of the returned (best) iterate
  double mu = 0;               ///< x^T y / nc at the end
  int factorizations = 0;
  double factor_seconds = 0;   ///< time in assembling + factorising K
  double seconds = 0;
  bool past_soft_time = false; ///< went on past EngineRun::soft_time (soft_time_extends)
  /// ended (TimeLimit) before a factorisation that could not end within
  /// max_time (InteriorPoint::factorization_fits)
  bool factorization_refused = false;
  int fake_iteration = -1;     ///< first iteration where the talk's test met tol with error > tol
  double fake_error = 0;       ///< the error there
  std::string note;            ///< why a NumericalError (or a TimeLimit before a factorisation) exit happened
  std::vector<double> history;
};

template <class Form>
class InteriorPoint {
 public:
  static constexpr int D = Form::dim;

  explicit InteriorPoint(Form& form) : form_(form) {
    const Index n = form.primal_size(), m = form.size(), nc = form.num_contacts();
    state_.resize(nc);
    d_.resize(n, m, nc);
    best_.resize(n, m, nc);
    r_d_.resize(n);
    r_p_.resize(m);
    rp_tilde_.resize(m);
    r_s_.setZero(nc);
    xi_.resize(m);
    dxs_.resize(m);
    dys_.resize(m);
  }

  /// Mehrotra's starting point adapted to L^d: the least-squares point of the
  /// linear equations with T = theta I, each cone block shifted into int L by
  /// a common amount (Mehrotra 1992, sec. 7). `it.s` holds the frozen s (or
  /// the initial s when coupled; replaced by ||x_T|| then). When its
  /// factorisation cannot end within `seconds_left` (factorization_fits),
  /// `it` is the centre of the cones, x = y = e, v = 0, unfactorised: the
  /// run that follows ends before its first factorisation (TimeLimit).
  void cold_start(Iterate& it, bool coupled, double seconds_left) {
    const Index nc = form_.num_contacts();
    it.v.setZero(form_.primal_size());
    it.x.setZero(form_.size());
    it.y.setZero(form_.size());
    form_.kkt().set_symmetric(form_.symmetric_kkt(false));  // factorize_uniform's matrix
    if (!factorization_fits(seconds_left)) {
      add_normal<D>(it.x, Vector::Ones(nc));
      add_normal<D>(it.y, Vector::Ones(nc));
      if (coupled) it.s.setZero(nc);
      return;
    }
    const double theta = form_.initial_scaling();
    form_.residuals(it, r_d_, r_p_);
    if (!form_.factorize_uniform(theta, regularization_delta(1e-12)))
      form_.factorize_uniform(theta, regularization_delta(1e-8));
    xi_.setZero();
    form_.direction_uniform(theta, xi_, r_d_, r_p_, d_);
    it.v = d_.v;
    double dx = 0, dy = 0;
    for (Index a = 0; a < nc; ++a) {
      dx = std::max(dx, -1.5 * lorentz_min_eigenvalue<D>(d_.x.template segment<D>(a * D)));
      dy = std::max(dy, -1.5 * lorentz_min_eigenvalue<D>(d_.y.template segment<D>(a * D)));
    }
    Vector xs = d_.x, ys = d_.y;
    add_normal<D>(xs, Vector::Constant(nc, dx));
    add_normal<D>(ys, Vector::Constant(nc, dy));
    double trace_x = 0, trace_y = 0;
    for (Index a = 0; a < nc; ++a) {
      trace_x += xs[a * D];
      trace_y += ys[a * D];
    }
    const double xy = xs.dot(ys);
    if (xy > 0 && trace_x > 0 && trace_y > 0) {
      dx += 0.5 * xy / trace_y;
      dy += 0.5 * xy / trace_x;
    }
    // Degenerate data (q = 0, f = 0, ...): fall back on the balanced e, theta^2 e.
    if (!(dx > 0)) dx = 1;
    if (!(dy > 0)) dy = 1;
    it.x = d_.x;
    it.y = d_.y;
    add_normal<D>(it.x, Vector::Constant(nc, dx));
    add_normal<D>(it.y, Vector::Constant(nc, dy));
    if (coupled)
      for (Index a = 0; a < nc; ++a)
        it.s[a] = frictionless(form_.mu()[a]) ? 0.0 : it.x.template segment<D - 1>(a * D + 1).norm();
  }

  /// Moves a (near-)boundary point into int L: every block gets at least
  /// the smallest spectral value `min_x` (resp. `min_y`).
  static void push_inside(Iterate& it, double min_x, double min_y) {
    for (Index a = 0; a < it.s.size(); ++a) {
      auto xa = it.x.template segment<D>(a * D);
      auto ya = it.y.template segment<D>(a * D);
      xa[0] += std::max(0.0, min_x - lorentz_min_eigenvalue<D>(xa));
      ya[0] += std::max(0.0, min_y - lorentz_min_eigenvalue<D>(ya));
    }
  }

  /// Runs the predictor-corrector from `it` (strictly interior). On return
  /// `it` is the best iterate met (lowest error). Each iteration, as in
  /// Mehrotra (1992) with NT scaling (Vandenberghe 2010, sec. 5.3):
  /// residuals and error, termination test, scaling update, factorisation,
  /// affine (predictor) step, combined (corrector) step, step length.
  IpmReport run(Iterate& it, const EngineRun& opt) {
    Stopwatch clock;
    IpmReport rep;
    start_progress();
    for (int k = 0;; ++k) {
      const double err = residuals_and_error(it, opt.coupled);
      if (terminated(k, err, it, opt, clock, rep)) break;
      if (!update_scaling(it, opt.coupled, rep)) break;
      if (!factorization_fits(opt, clock, rep)) break;
      if (!factorize(opt, rep)) break;
      const double mu = it.x.dot(it.y) / double(form_.num_contacts());
      const double sigma = affine_step(it, mu, opt);
      combined_direction(sigma, mu, opt);
      if (!take_step(it, opt, k, rep)) break;
    }
    it = best_;
    rep.error = best_error_;
    rep.seconds = clock.seconds();
    return rep;
  }

  /// dx for the data change w -> w + E p at the last factorisation (s
  /// frozen): the derivative of the central point with respect to s, for
  /// the ACLM Newton step. `r_d` is zero, xi = 0.
  void frozen_sensitivity(const Vector& p, Vector& dx, int refinement) {
    xi_.setZero();
    r_d_.setZero();
    rp_tilde_.setZero();
    add_friction_shift<D>(rp_tilde_, p, form_.mu());
    form_.direction(state_, xi_, r_d_, rp_tilde_, d_, refinement);
    dx = d_.x;
  }

 private:
  Vec<D> lambda(Index a) const { return state_.scaling[std::size_t(a)].lambda; }

  void start_progress() {
    best_error_ = std::numeric_limits<double>::infinity();
    last_improvement_ = 0;
    small_steps_ = 0;
  }

  /// Residuals r_d, r_p (and r_s = s - ||x_T|| when coupled; r_s = s on a
  /// frictionless contact, whose s is 0) at `it`, and its error:
  /// frozen-s natural map, or FCLIB when coupled.
  double residuals_and_error(const Iterate& it, bool coupled) {
    form_.residuals(it, r_d_, r_p_);
    if (coupled)
      for (Index a = 0; a < form_.num_contacts(); ++a)
        r_s_[a] = frictionless(form_.mu()[a]) ? it.s[a]
                                              : it.s[a] - it.x.template segment<D - 1>(a * D + 1).norm();
    return form_.error(it, !coupled);
  }

  /// Keeps the best iterate, then the termination test: error <= tol, the
  /// budgets, the callback, no progress, slow progress (time to polish).
  /// True with rep.exit set when the run ends at iteration k.
  bool terminated(int k, double err, const Iterate& it, const EngineRun& opt,
                  const Stopwatch& clock, IpmReport& rep) {
    if (!std::isfinite(err)) return fail(rep, "non-finite error");
    if (opt.record_history) rep.history.push_back(err);
    if (err < best_error_) {
      best_error_ = err;
      best_ = it;
      last_improvement_ = k;
    }
    rep.iterations = k;
    rep.mu = it.x.dot(it.y) / double(form_.num_contacts());
    const double fake_tol = opt.fake_residual > 0 ? opt.fake_residual : opt.tol;
    if (rep.fake_iteration < 0 && err > opt.tol && talk_residual(it) <= fake_tol) {
      rep.fake_iteration = k;
      rep.fake_error = err;
    }
    // k = 0 is the starting point, not an iteration: callbacks see the
    // steps numbered 1, 2, ... (continued across ACLM's inner runs).
    if (opt.callback && k > 0) {
      const IterationInfo info{opt.iteration_offset + k, err, true, opt.seconds_offset + clock.seconds()};
      if (callback_requests_stop(*opt.callback, info)) return exit_with(rep, IpmExit::Stopped);
    }
    if (err <= opt.tol) return exit_with(rep, IpmExit::Converged);
    if (k >= opt.max_iter) return exit_with(rep, IpmExit::MaxIterations);
    if (clock.seconds() > opt.max_time) return exit_with(rep, IpmExit::TimeLimit);
    bests_[std::size_t(k % bests_.size())] = best_error_;
    if (opt.soft_time > 0 && opt.seconds_offset + clock.seconds() > opt.soft_time) {
      const double before = k >= kSoftTimeRateWindow ? best_before(k, kSoftTimeRateWindow)
                                                     : std::numeric_limits<double>::infinity();
      if (k == 0 || !soft_time_extends(best_error_, before, opt.tol, clock.seconds() / k,
                                       opt.max_time - clock.seconds()))
        return exit_with(rep, IpmExit::TimeLimit);
      rep.past_soft_time = true;
    }
    if (k - last_improvement_ > opt.stall_window) return exit_with(rep, IpmExit::NoProgress);
    if (k >= 3 && best_error_ < opt.slow_below && best_error_ > 0.5 * best_before(k, 3))
      return exit_with(rep, IpmExit::SlowProgress);
    return false;
  }

  /// The best error j <= kSoftTimeRateWindow iterations before k (k >= j).
  double best_before(int k, int j) const { return bests_[std::size_t((k - j) % int(bests_.size()))]; }

  static bool exit_with(IpmReport& rep, IpmExit e) {
    rep.exit = e;
    return true;
  }
  static bool fail(IpmReport& rep, const char* why) {
    rep.exit = IpmExit::NumericalError;
    rep.note = why;
    return true;
  }

  /// NT scaling of every contact and, when coupled, the subgradient n_a of
  /// ||x_T||. False (NumericalError) when an iterate left the cone.
  bool update_scaling(Iterate& it, bool coupled, IpmReport& rep) {
    const Index nc = form_.num_contacts();
    for (Index a = 0; a < nc; ++a) {
      auto xa = it.x.template segment<D>(a * D);
      auto ya = it.y.template segment<D>(a * D);
      auto& sc = state_.scaling[std::size_t(a)];
      if (sc.compute(xa, ya)) continue;
      // Rounding put the point on (or past) the boundary: the step kept it
      // inside in exact arithmetic, so restore a tiny relative margin.
      keep_inside(xa);
      keep_inside(ya);
      if (!sc.compute(xa, ya))
        return !fail(rep, "an iterate reached the cone boundary in floating point");
    }
    if (coupled)
      for (Index a = 0; a < nc; ++a) {
        const auto xt = it.x.template segment<D - 1>(a * D + 1);
        const double nt = xt.norm();
        auto& na = state_.normal[std::size_t(a)];
        na.setZero();  // and stays 0 on a frictionless contact: no coupling
        if (nt > 0 && !frictionless(form_.mu()[a])) na.template tail<D - 1>() = xt / nt;
      }
    return true;
  }

  /// Whether the Newton matrix' next factorisation can end within
  /// `seconds_left`, at the least time its symbolic analysis allows
  /// (KktSystem::least_factorization_seconds). A factorisation cannot be
  /// interrupted: on a sphere pile of 10^5 contacts one took 100 to 200 s,
  /// and a run asked for 20 s returned after 203 s (docs/results.md).
  bool factorization_fits(double seconds_left) {
    return form_.kkt().least_factorization_seconds() <= seconds_left;
  }
  /// The same before an iteration's factorisation; when it does not fit,
  /// the run ends with TimeLimit and says why.
  bool factorization_fits(const EngineRun& opt, const Stopwatch& clock, IpmReport& rep) {
    form_.kkt().set_symmetric(form_.symmetric_kkt(opt.coupled));
    const double least = form_.kkt().least_factorization_seconds();
    if (least <= opt.max_time - clock.seconds()) return true;
    rep.exit = IpmExit::TimeLimit;
    rep.factorization_refused = true;
    char text[160];
    std::snprintf(text, sizeof text,
                  "the next factorisation, at least %.3g s by its symbolic analysis, would not end "
                  "within max_time: not started",
                  least);
    rep.note = text;
    return false;
  }

  /// Assembles and factorises the Newton matrix, with a static
  /// regularisation grown x100 per failed attempt (up to 6).
  bool factorize(const EngineRun& opt, IpmReport& rep) {
    Stopwatch fclock;
    bool ok = false;
    for (int attempt = 0; attempt < 6 && !ok; ++attempt) {
      const double rel = attempt == 0 ? opt.step.regularization
                                      : std::max(opt.step.regularization, 1e-14) * std::pow(100.0, attempt);
      ok = form_.factorize(state_, opt.coupled, regularization_delta(rel));
      ++rep.factorizations;
    }
    rep.factor_seconds += fclock.seconds();
    return ok || !fail(rep, "the Newton matrix could not be factorised, even regularised");
  }

  /// Predictor: the affine-scaling direction (xi = -lambda) and from its
  /// step Mehrotra's centring parameter sigma = (mu_aff / mu)^3.
  double affine_step(const Iterate& it, double mu, const EngineRun& opt) {
    const Index nc = form_.num_contacts();
    rp_tilde_ = r_p_;
    if (opt.coupled) add_friction_shift<D>(rp_tilde_, Vector(-r_s_), form_.mu());
    for (Index a = 0; a < nc; ++a) xi_.template segment<D>(a * D) = -lambda(a);
    newton_direction(rp_tilde_, opt);
    const double alpha_aff = std::min(1.0, max_step());
    const double mu_aff = (it.x + alpha_aff * d_.x).dot(it.y + alpha_aff * d_.y) / double(nc);
    return std::clamp(std::pow(std::max(mu_aff, 0.0) / mu, 3.0), 0.0, opt.step.sigma_max);
  }

  /// Corrector: xi = lambda \ (sigma mu e - lambda o lambda - dxa~ o dya~),
  /// centring plus the second-order term of the affine direction.
  void combined_direction(double sigma, double mu, const EngineRun& opt) {
    for (Index a = 0; a < form_.num_contacts(); ++a) {
      const Vec<D> lam = lambda(a);
      Vec<D> rc = -jordan::product<D>(lam, lam) -
                  jordan::product<D>(Vec<D>(dxs_.template segment<D>(a * D)),
                                     Vec<D>(dys_.template segment<D>(a * D)));
      rc[0] += sigma * mu;
      xi_.template segment<D>(a * D) = jordan_quotient<D>(lam, rc);
    }
    newton_direction(rp_tilde_, opt);
  }

  /// Step length gamma * (largest step in the cones), kept in the
  /// neighbourhood, and the update. False when the run ends (no admissible
  /// step, or three steps below 1e-8: SmallStep).
  bool take_step(Iterate& it, const EngineRun& opt, int k, IpmReport& rep) {
    double alpha = std::min(1.0, opt.step.step_fraction * max_step());
    alpha = centred_step(it, alpha, opt.step.neighbourhood);
    if (!std::isfinite(alpha) || !(alpha > 0)) return !fail(rep, "no admissible step");
    if (form_.primal_size() > 0) it.v += alpha * d_.v;
    it.x += alpha * d_.x;
    it.y += alpha * d_.y;
    if (opt.coupled) it.s += alpha * d_.s;
    small_steps_ = alpha < 1e-8 ? small_steps_ + 1 : 0;
    if (small_steps_ < 3) return true;
    rep.iterations = k + 1;
    rep.exit = IpmExit::SmallStep;
    return false;
  }

  /// z0 >= (1 + 1e-13) ||z1|| (and z0 > 0): a relative change at rounding level.
  template <class Segment>
  static void keep_inside(Segment&& z) {
    const double nb = z.template tail<D - 1>().norm();
    const double floor_value = std::max(nb * (1 + 1e-13), 1e-300);
    if (z[0] < floor_value) z[0] = floor_value;
  }

  double regularization_delta(double relative) const {
    return relative * form_.diagonal_scale();
  }

  void newton_direction(const Vector& rp_tilde, const EngineRun& opt) {
    form_.direction(state_, xi_, r_d_, rp_tilde, d_, opt.step.refinement);
    const Index nc = form_.num_contacts();
    if (opt.coupled)
      for (Index a = 0; a < nc; ++a)
        d_.s[a] = state_.normal[std::size_t(a)].dot(d_.x.template segment<D>(a * D)) - r_s_[a];
    for (Index a = 0; a < nc; ++a) {
      const auto& sc = state_.scaling[std::size_t(a)];
      dxs_.template segment<D>(a * D) = sc.Tinv * d_.x.template segment<D>(a * D);
      dys_.template segment<D>(a * D) = sc.T * d_.y.template segment<D>(a * D);
    }
  }

  /// Largest alpha keeping lambda + alpha dx~ and lambda + alpha dy~ in L
  /// (equivalently x + alpha dx, y + alpha dy: T is a cone automorphism).
  double max_step() const {
    double alpha = std::numeric_limits<double>::infinity();
    for (Index a = 0; a < form_.num_contacts(); ++a) {
      const Vec<D> lam = lambda(a);
      alpha = std::min({alpha, max_step_in_cone<D>(lam, dxs_.template segment<D>(a * D)),
                        max_step_in_cone<D>(lam, dys_.template segment<D>(a * D))});
    }
    return alpha;
  }

  /// Backtracks alpha until every contact stays in the wide neighbourhood
  ///   lambda_min(lambda_a)^2 >= eta mu   (lambda_a the NT-scaled point)
  /// of the central path. Off this neighbourhood x^T y can be small while
  /// the spectral frames of x_a and y_a still differ by O(sqrt(mu)), which
  /// is the natural-map error, instead of O(mu) (Monteiro & Tsuchiya 2000
  /// for neighbourhoods of SOCP central paths). lambda_min(lambda) comes from
  /// det(lambda)^2 = det x det y and lambda0^2 = (sqrt(det x det y) + x^T y)/2.
  double centred_step(const Iterate& it, double alpha, double eta) const {
    if (!(eta > 0)) return alpha;
    // Never ask more than half the centrality the current point has.
    const double now = centrality(it, 0.0);
    const double target = std::min(eta, 0.5 * std::max(now, 0.0));
    for (int trial = 0; trial < 30; ++trial, alpha *= 0.8)
      if (centrality(it, alpha) >= target) return alpha;
    return alpha;
  }

  /// min_a lambda_min(lambda_a)^2 / mu at x + alpha dx, y + alpha dy
  /// (-1 outside the cone).
  double centrality(const Iterate& it, double alpha) const {
    const Index nc = form_.num_contacts();
    double total = 0, worst = std::numeric_limits<double>::infinity();
    for (Index a = 0; a < nc; ++a) {
      const Vec<D> xa = it.x.template segment<D>(a * D) + alpha * d_.x.template segment<D>(a * D);
      const Vec<D> ya = it.y.template segment<D>(a * D) + alpha * d_.y.template segment<D>(a * D);
      const double xy = xa.dot(ya), dxy = lorentz_det<D>(xa) * lorentz_det<D>(ya);
      total += xy;
      if (!(dxy > 0) || !(xa[0] > 0) || !(ya[0] > 0)) return -1;
      const double g = std::sqrt(dxy), l0 = std::sqrt(0.5 * (g + xy));
      const double lmin = g / (l0 + std::sqrt(std::max(l0 * l0 - g, 0.0)));  // = l0 - ||l1||
      worst = std::min(worst, lmin * lmin);
    }
    return total > 0 ? worst / (total / double(nc)) : -1;
  }

  /// The NIPM stopping quantity of Acary 2025 (talk, slide "Nonsmooth
  /// Interior-Point Method"; docs/references.md)
  /// max(||r_p||inf, ||r_d||inf, ||r_s||inf, ||x o y||), in Lorentz units.
  double talk_residual(const Iterate& it) const {
    double comp = 0;
    for (Index a = 0; a < form_.num_contacts(); ++a)
      comp += jordan::product<D>(Vec<D>(it.x.template segment<D>(a * D)),
                                 Vec<D>(it.y.template segment<D>(a * D)))
                  .squaredNorm();
    double res = std::sqrt(comp);
    if (r_p_.size()) res = std::max(res, r_p_.cwiseAbs().maxCoeff());
    if (r_d_.size()) res = std::max(res, r_d_.cwiseAbs().maxCoeff());
    if (r_s_.size()) res = std::max(res, r_s_.cwiseAbs().maxCoeff());
    return res;
  }

  Form& form_;
  ContactState<D> state_;
  Iterate d_, best_;
  Vector r_d_, r_p_, rp_tilde_, r_s_, xi_, dxs_, dys_;
  // best error of the last iterations, the slow-progress test's (3 back)
  // and the soft time's (kSoftTimeRateWindow back)
  std::array<double, kSoftTimeRateWindow + 1> bests_{};
  static_assert(kSoftTimeRateWindow >= 3, "the ring serves the slow-progress test too");
  double best_error_ = 0;
  int last_improvement_ = 0, small_steps_ = 0;
};

}  // namespace ipm
}  // namespace fcsolve
