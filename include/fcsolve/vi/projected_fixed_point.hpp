// Projection methods for the variational inequality form of FC/II
// (Acary, Bremond & Huber 2018, sec. 4.1; docs/references.md):
//
//   -F(r) in N_K(r),   F(r) = W r + q + g(W r + q)   (u~, De Saxce's velocity)
//
//   fixed point [FP-VI]:   r <- rb = P_K(r - rho F(r))
//   extragradient [EG-VI]: rb = P_K(r - rho F(r)),  r <- P_K(r - rho F(rb))
//                          (Korpelevich 1976)
//
// with the self-adaptive step of Khobotov (1987) as used by FP-VI-UPK /
// EG-VI-UPK: rho shrinks until rho ||F(r) - F(rb)|| <= L ||r - rb|| and grows
// again when the ratio falls below L_min. F(r) is u~ at r, so the FCLIB error
// ||r - P_K(r - F(r))|| / ||q|| comes for free every iteration.
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
inline const char* to_string(StepRule r) { return enum_to_string(r); }

struct ProjectedFixedPointSettings : SolverSettings {
  ProjectionVariant variant = ProjectionVariant::ExtraGradient;
  StepRule step = StepRule::SelfAdaptive;
  double rho = 0;            ///< initial (fixed: the) step; 0: 1 / ||W||_1
  double shrink = 2.0 / 3.0;  ///< rho <- shrink * rho while the step is too long
  double ratio_max = 0.9;    ///< L: accept when rho ||F(r) - F(rb)|| <= L ||r - rb||
  double ratio_min = 0.3;    ///< L_min: grow rho when the ratio falls below it
  int max_line_search = 50;
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
    validate_dimension(p.d, d);
    validate(p);
    problem_.emplace(p);
    W_.compute(p.W);
    const Index m = p.size();
    F_.resize(m);
    Fb_.resize(m);
    rb_.resize(m);
    u_.resize(m);
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
    double rho = rho0_;
    double error = evaluate(r, F_);  // F_ = F(r), error of r
    for (int k = 1; k <= settings_.max_iter && error > settings_.tol; ++k) {
      info_.iterations = k;
      FCSOLVE_NO_MALLOC_BEGIN();
      const double ratio = step(r, rho);  // rb_ = the next iterate
      r = rb_;
      error = evaluate(r, F_);
      FCSOLVE_NO_MALLOC_END();
      if (settings_.step == StepRule::SelfAdaptive && ratio < settings_.ratio_min) rho /= settings_.shrink;
      if (!std::isfinite(error)) { info_.status = Status::NumericalError; break; }
      if (settings_.record_history) info_.history.push_back(error);
      if (callback_requests_stop(settings_.callback,
                                 IterationInfo{k, error, true, clock.seconds()})) {
        info_.status = Status::Stopped;
        break;
      }
      if (clock.seconds() > settings_.max_time) { info_.status = Status::TimeLimit; break; }
    }
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

  /// rb_ = the next iterate from r (F_ = F(r)). The self-adaptive rule
  /// shrinks rho until the step is short enough and returns the accepted
  /// ratio rho ||F(r) - F(rb)|| / ||r - rb||; the fixed rule returns 1.
  double step(const Eigen::Ref<const Vector>& r, double& rho) {
    const bool extragradient = settings_.variant == ProjectionVariant::ExtraGradient;
    if (settings_.step == StepRule::Fixed) {
      project_step(r, F_, rho, rb_);
      if (extragradient) {
        evaluate(rb_, Fb_);
        project_step(r, Fb_, rho, rb_);  // r <- P_K(r - rho F(rb))
      }
      return 1;
    }
    double ratio = 0;
    for (int ls = 0; ls <= settings_.max_line_search; ++ls) {
      project_step(r, F_, rho, rb_);
      const double dr = (r - rb_).norm();
      if (dr == 0) break;
      evaluate(rb_, Fb_);
      ratio = rho * (F_ - Fb_).norm() / dr;
      if (ratio <= settings_.ratio_max) break;
      rho *= settings_.shrink;
    }
    if (extragradient) project_step(r, Fb_, rho, rb_);  // r <- P_K(r - rho F(rb))
    return ratio;
  }

  /// F = u~(x) = W x + q + g(W x + q); returns the FCLIB error of x. u_ = W x + q.
  double evaluate(const Eigen::Ref<const Vector>& x, Vector& F) {
    const LocalProblemView& p = *problem_;
    W_.multiply(x, u_);
    u_ += p.q;
    double sq = 0;
    for (Index a = 0; a < p.num_contacts(); ++a) {
      const typename Cone::Vec ua = u_.template segment<d>(a * d);
      const typename Cone::Vec Fa = Cone::modified_velocity(ua, p.mu[a]);
      F.template segment<d>(a * d) = Fa;
      const typename Cone::Vec xa = x.template segment<d>(a * d);
      sq += (xa - Cone::project(typename Cone::Vec(xa - Fa), p.mu[a])).squaredNorm();
    }
    return std::sqrt(sq) / scale_;
  }

  /// out = P_K(x - rho G), contact by contact.
  void project_step(const Eigen::Ref<const Vector>& x, const Vector& G, double rho, Vector& out) const {
    const LocalProblemView& p = *problem_;
    for (Index a = 0; a < p.num_contacts(); ++a) {
      const typename Cone::Vec z = x.template segment<d>(a * d) - rho * G.template segment<d>(a * d);
      out.template segment<d>(a * d) = Cone::project(z, p.mu[a]);
    }
  }

  Settings settings_;
  SolverInfo info_;
  std::optional<LocalProblemView> problem_;
  Storage W_;
  Vector F_, Fb_, rb_, u_;
  double scale_ = 1, rho0_ = 1;
};

}  // namespace fcsolve
