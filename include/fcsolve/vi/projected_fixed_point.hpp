// Projection methods for the variational inequality form of FC/II
// (Acary, Bremond & Huber 2018, sec. 4.1; docs/references.md):
//
//   -F(r) in N_K(r),   F(r) = W r + q + g(W r + q)   (u~, De Saxce's velocity)
//
//   fixed point [FP-VI]:   r <- rb = P_K(r - rho F(r))
//   extragradient [EG-VI]: rb = P_K(r - rho F(r)),  then one of
//     EgSecondStep::Korpelevich: r <- P_K(r  - rho F(rb))   (Korpelevich 1976)
//     EgSecondStep::Predictor:   r <- P_K(rb - rho F(rb))
//
// with the self-adaptive step of Khobotov (1987) as used by FP-VI-UPK /
// EG-VI-UPK: rho shrinks until rho ||F(r) - F(rb)|| <= L ||r - rb|| and grows
// again when the ratio falls below L_min.
//
// The predictor second step is the one of Siconos' VI_EG: two projected
// steps of length rho, the step length checked once. No convergence theory
// covers it that we know of, but none covers either second step on the
// Coulomb VI, which is not monotone; on the shared FCLIB problems and the
// generated corpus it takes 4 to 10 times fewer iterations than
// Korpelevich's (docs/results.md, "vi-eg: the second step from the trial
// point"), so it is vi-eg's default.
//
// Cost per step: the fixed point takes rb, F(rb) of the accepted trial as the
// next iterate (one evaluation of F per trial, none more); the extragradient
// needs F(r) at its new iterate as well. The FCLIB error
// e(r) = ||r - P_K(r - F(r))|| / ||q|| is not computed every step: the trial
// step already gives e_rho(r) = ||r - P_K(r - rho F(r))||, and since
// rho -> e_rho is nondecreasing while rho -> e_rho / rho is nonincreasing
// (Gafni & Bertsekas 1984, Lemma 1; docs/references.md)
//
//   e_rho / max(1, rho)  <=  e_1 = e(r) ||q||  <=  e_rho / min(1, rho).
//
// The lower bound proves that r has not converged. Otherwise the exact error
// (one projection per contact) is computed when the upper bound or a
// prediction from the last exact value says it may be below tol, or every
// error_refresh steps; the stopping decision is always the exact error's.
//
// The fixed point with StepRule::Fixed is De Saxce's fixed point (De Saxce
// & Feng 1998; Acary, Bremond & Huber 2018, sec. 4.1 [FP-DS], Siconos'
// DSFP): r <- P_K(r - rho (u + g(u))), u = W r + q, with a constant rho.
// StepRule::SelfAdaptive is the rule above ([FP-VI-UPK]).
#pragma once

#include <fcsolve/config.hpp>
#include <fcsolve/core/enum_names.hpp>
#include <fcsolve/core/exceptions.hpp>
#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/core/solver_settings.hpp>
#include <fcsolve/core/timer.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/problem/local_problem.hpp>
#include <fcsolve/problem/validate.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace fcsolve {

enum class ProjectionVariant { FixedPoint, ExtraGradient };

/// How rho evolves: the self-adaptive rule above, or constant.
enum class StepRule { SelfAdaptive, Fixed };

inline constexpr EnumName<StepRule> kStepRuleNames[] = {{StepRule::SelfAdaptive, "self-adaptive"},
                                                       {StepRule::Fixed, "fixed"}};
constexpr const auto& enum_names(StepRule) { return kStepRuleNames; }

/// The extragradient's second step (file comment): from r or from rb.
enum class EgSecondStep { Predictor, Korpelevich };

inline constexpr EnumName<EgSecondStep> kEgSecondStepNames[] = {
    {EgSecondStep::Predictor, "predictor"}, {EgSecondStep::Korpelevich, "korpelevich"}};
constexpr const auto& enum_names(EgSecondStep) { return kEgSecondStepNames; }

struct ProjectedFixedPointSettings : SolverSettings {
  ProjectionVariant variant = ProjectionVariant::ExtraGradient;
  StepRule step = StepRule::SelfAdaptive;
  EgSecondStep second_step = EgSecondStep::Predictor;  ///< ExtraGradient only
  double rho = 0;            ///< initial (fixed: the) step; 0: 1 / ||W||_1
  double shrink = 2.0 / 3.0;  ///< rho <- shrink * rho while the step is too long
  double ratio_max = 0.9;    ///< L: accept when rho ||F(r) - F(rb)|| <= L ||r - rb||
  double ratio_min = 0.3;    ///< L_min: grow rho when the ratio falls below it
  int max_line_search = 50;
  /// Steps between two exact error evaluations while the error bounds of the
  /// trial step leave the convergence test open (file comment).
  int error_refresh = 10;
};

template <class Cone, class Storage>
class ProjectedFixedPoint {
 public:
  static constexpr int d = Cone::dim;
  using Settings = ProjectedFixedPointSettings;

  explicit ProjectedFixedPoint(const Settings& s = {}) : settings_(s) {}
  Settings& settings() { return settings_; }
  const Settings& settings() const { return settings_; }
  const SolverInfo& info() const { return info_; }

  /// Validates p (InvalidProblem on inconsistent data) and prepares the
  /// step. The viewed data must outlive *this.
  ProjectedFixedPoint& compute(const LocalProblemView& p) {
    Stopwatch clock;
    problem_.emplace(validated(p, d));
    W_.compute(p.W);
    const Index m = p.size();
    F_.resize(m);
    Fb_.resize(m);
    rb_.resize(m);
    u_.resize(m);
    ub_.resize(m);
    scale_ = error_scale(p.q.norm());
    // ||W||_1 bounds the Lipschitz constant of r -> W r; start at 1 / that
    double norm1 = 0;
    for (Index j = 0; j < p.W.outerSize(); ++j) {
      double col = 0;
      for (SparseMap::InnerIterator it(p.W, j); it; ++it) col += std::abs(it.value());
      norm1 = std::max(norm1, col);
    }
    rho0_ = settings_.rho > 0 ? settings_.rho : (norm1 > 0 ? 1.0 / norm1 : 1.0);
    info_ = SolverInfo();
    info_.setup_seconds = clock.seconds();
    return *this;
  }

  /// r: warm start in, solution out; u = W r + q on return.
  const SolverInfo& solve(Eigen::Ref<Vector> r, Eigen::Ref<Vector> u) {
    Stopwatch clock;
    check_solve_arguments(r, u);
    info_.status = Status::MaxIterations;
    info_.iterations = 0;
    info_.history.clear();
    info_.message.clear();
    rho_ = rho0_;
    predict_ = 1;
    since_exact_ = 0;
    evaluate(r, F_, u_);  // F_ = F(r), u_ = W r + q
    double error = exact_error(r);
    bool converged = error <= settings_.tol;
    if (!converged) trial_step(r);
    for (int k = 1; k <= settings_.max_iter && !converged; ++k) {
      info_.iterations = k;
      FCSOLVE_NO_MALLOC_BEGIN();
      if (settings_.variant == ProjectionVariant::ExtraGradient) {
        // r <- P_K(r - rho F(rb)) or P_K(rb - rho F(rb)); project_step reads
        // a contact's x before it writes its out, so rb_ may be both
        if (settings_.second_step == EgSecondStep::Korpelevich)
          project_step(r, Fb_, rho_, rb_);
        else
          project_step(rb_, Fb_, rho_, rb_);
        r = rb_;
        evaluate(r, F_, u_);
      } else {  // r <- rb, whose F and u the trial computed
        r = rb_;
        F_.swap(Fb_);
        u_.swap(ub_);
      }
      if (settings_.step == StepRule::SelfAdaptive && ratio_ < settings_.ratio_min)
        rho_ /= settings_.shrink;
      trial_step(r);  // the next trial point, and the bounds on e(r)
      bool exact = false;
      error = check_error(r, exact);
      FCSOLVE_NO_MALLOC_END();
      if (!std::isfinite(error)) { info_.status = Status::NumericalError; break; }
      converged = error <= settings_.tol;
      if (settings_.record_history) info_.history.push_back(error);
      if (callback_requests_stop(settings_.callback,
                                 IterationInfo{k, error, exact, clock.seconds()})) {
        info_.status = Status::Stopped;
        break;
      }
      if (converged) break;
      if (clock.seconds() > settings_.max_time) { info_.status = Status::TimeLimit; break; }
    }
    // the reported error is the exact one, whichever test ended the loop
    if (info_.status != Status::NumericalError) error = exact_error(r);
    if (error <= settings_.tol) info_.status = Status::Converged;
    u = u_;
    info_.error = error;
    info_.solve_seconds = clock.seconds();
    return info_;
  }

 private:
  void check_solve_arguments(const Eigen::Ref<Vector>& r, const Eigen::Ref<Vector>& u) const {
    const Index m = problem_ ? problem_->size() : 0;
    fcsolve::check_solve_arguments("ProjectedFixedPoint", problem_.has_value(), r, m, u, m, "u");
  }

  /// rb = P_K(r - rho F(r)) with F_ = F(r), shrinking rho until
  /// rho ||F(r) - F(rb)|| <= L ||r - rb|| (Khobotov 1987; StepRule::Fixed:
  /// one trial, rho kept). Leaves rb_, Fb_, ub_ at the accepted trial,
  /// step_residual_ = ||r - rb||, ratio_.
  void trial_step(const Eigen::Ref<const Vector>& r) {
    ratio_ = 0;
    const bool fixed = settings_.step == StepRule::Fixed;
    for (int ls = 0; ls <= (fixed ? 0 : settings_.max_line_search); ++ls) {
      step_residual_ = std::sqrt(project_step(r, F_, rho_, rb_));
      const double dF = std::sqrt(evaluate(rb_, Fb_, ub_, &F_));
      if (step_residual_ == 0) break;
      ratio_ = rho_ * dF / step_residual_;
      if (fixed || ratio_ <= settings_.ratio_max) break;
      rho_ *= settings_.shrink;
    }
  }

  /// The error of r (F_ = F(r)) as the file comment bounds it from the last
  /// trial step; exact (one projection) only when the bounds leave it open
  /// and the prediction from the last exact value, or the refresh, asks.
  double check_error(const Eigen::Ref<const Vector>& r, bool& exact) {
    const double upper = step_residual_ / (std::min(1.0, rho_) * scale_);
    const double lower = step_residual_ / (std::max(1.0, rho_) * scale_);
    ++since_exact_;
    exact = false;
    const double predicted = std::clamp(predict_ * upper, lower, upper);
    if (lower > settings_.tol) return predicted;  // not converged, proven
    // upper <= tol proves convergence up to rounding; the exact error, once,
    // makes the stopping decision the FCLIB one
    if (upper > settings_.tol && predicted > settings_.tol &&
        since_exact_ < settings_.error_refresh)
      return predicted;
    exact = true;
    const double error = exact_error(r);
    predict_ = upper > 0 ? error / upper : 1;
    since_exact_ = 0;
    return error;
  }

  /// F = u~(x) = W x + q + g(W x + q), u = W x + q; with Fref, returns
  /// ||F - Fref||^2 (the Khobotov ratio's numerator), in the same pass.
  double evaluate(const Eigen::Ref<const Vector>& x, Vector& F, Vector& u,
                  const Vector* Fref = nullptr) const {
    const LocalProblemView& p = *problem_;
    W_.multiply(x, u);
    u += p.q;
    double sq = 0;
    for (Index a = 0; a < p.num_contacts(); ++a) {
      const typename Cone::Vec ua = u.template segment<d>(a * d);
      const typename Cone::Vec Fa = Cone::modified_velocity(ua, p.mu[a]);
      F.template segment<d>(a * d) = Fa;
      if (Fref) sq += (Fa - Fref->template segment<d>(a * d)).squaredNorm();
    }
    return sq;
  }

  /// FCLIB error ||x - P_K(x - F(x))|| / ||q|| with F_ = F(x).
  double exact_error(const Eigen::Ref<const Vector>& x) const {
    const LocalProblemView& p = *problem_;
    double sq = 0;
    for (Index a = 0; a < p.num_contacts(); ++a) {
      const typename Cone::Vec xa = x.template segment<d>(a * d);
      const typename Cone::Vec Fa = F_.template segment<d>(a * d);
      sq += (xa - Cone::project(typename Cone::Vec(xa - Fa), p.mu[a])).squaredNorm();
    }
    return std::sqrt(sq) / scale_;
  }

  /// out = P_K(x - rho G), contact by contact; returns ||x - out||^2.
  double project_step(const Eigen::Ref<const Vector>& x, const Vector& G, double rho,
                      Vector& out) const {
    const LocalProblemView& p = *problem_;
    double sq = 0;
    for (Index a = 0; a < p.num_contacts(); ++a) {
      const typename Cone::Vec xa = x.template segment<d>(a * d);
      const typename Cone::Vec pa = Cone::project(typename Cone::Vec(xa - rho * G.template segment<d>(a * d)), p.mu[a]);
      out.template segment<d>(a * d) = pa;
      sq += (xa - pa).squaredNorm();
    }
    return sq;
  }

  Settings settings_;
  SolverInfo info_;
  std::optional<LocalProblemView> problem_;
  Storage W_;
  Vector F_, Fb_, rb_, u_, ub_;  // F and u at r and at the trial point rb
  double scale_ = 1, rho0_ = 1;
  double rho_ = 1, ratio_ = 0, step_residual_ = 0;  // the current step
  double predict_ = 1;   // e(r) / upper bound at the last exact evaluation
  int since_exact_ = 0;  // steps since the last exact error
};

}  // namespace fcsolve
