// The proximal point method on the global problem FC/I(M, H, f, w, mu),
// solved natively in (v, r), W = H^T M^-1 H never formed (Rockafellar 1976;
// Acary, Bremond & Huber 2018, sec. on the proximal point method). The
// subproblem of proximal_point.hpp, the contact law with u + alpha (r - r_k)
// in place of u, is on FC/I
//   M v = H r + f,   u = H^T v + (w - alpha r_k) + alpha r,
// i.e. FC/I with w' = w - alpha r_k and a contact compliance alpha: the
// global Newton's compliant form (newton/global_newton.hpp). Its Jacobian's
// r-block B + alpha A is regular where B alone is not (contacts sticking on
// a rank-deficient H), as W + alpha I is in the reduced form.
//
// The outer loop is ProximalPointLoop's (proximal_point_loop.hpp); success
// is declared only on the FCLIB global error of (r, v) of the original
// problem (problem/error.hpp: complementarity with u = H^T v + w, and
// equilibrium). The inner Newton's compute() (factorisation of M, pattern
// and symbolic analysis of its matrix) runs once, in compute(); a new
// subproblem rewrites w' in place and sets the compliance (O(nnz H)).
//
// alpha's unit is mean diag(H^T diag(M)^-1 H), the lumped W^aa the global
// Newton's rho strategies already use: O(nnz H), where mean diag(W) needs
// M^-1 H (one solve per contact unknown). It is exact for a diagonal M and
// of the right order otherwise (rigid bodies: the inertia's off-diagonal
// terms only); alpha_min and the failure rule absorb the rest.
//
// Bilateral constraints (G, b) are not handled by the global Newton: the
// catalogue entry solves those problems in the reduced form (ppa).
#pragma once

#include <fcsolve/cone/cones.hpp>
#include <fcsolve/core/exceptions.hpp>
#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/core/timer.hpp>
#include <fcsolve/formulation/alart_curnier.hpp>
#include <fcsolve/newton/global_newton.hpp>
#include <fcsolve/ppa/proximal_point_loop.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/problem/validate.hpp>

#include <cmath>
#include <optional>

namespace fcsolve {

template <class Cone, class Inner = GlobalNewton<AlartCurnierFunction, Cone>>
class ProximalPointGlobal : public ProximalPointLoop<ProximalPointGlobal<Cone, Inner>, Inner> {
  static_assert(is_cone_v<Cone>, "Cone must be a cone policy (cone/cones.hpp)");
  static_assert(Inner::d == Cone::dim, "the inner solver must be built for the same cone");
  using Base = ProximalPointLoop<ProximalPointGlobal, Inner>;
  friend Base;
  using Base::info_, Base::inner_, Base::settings_;

 public:
  using Base::d;
  explicit ProximalPointGlobal(const typename Base::Settings& s = {}) : Base(s) {}

  /// Validates p, factorises M and fixes the inner Newton's pattern (with the
  /// inner settings as they are now). The viewed data must outlive the
  /// solver. Throws InvalidProblem for bad data or a singular M, UsageError
  /// for bilateral constraints.
  ProximalPointGlobal& compute(const GlobalProblemView& p) {
    Stopwatch clock;
    if (p.has_bilateral())
      throw UsageError("ProximalPointGlobal does not handle bilateral constraints (G, b): use ProximalPoint");
    problem_.emplace(validated(p, d));
    shifted_w_ = p.w;
    // the subproblem: the same M, H, f, mu, with w' = w - alpha r_k (ours)
    subproblem_.emplace(p.d, p.M, p.H, p.f, VectorMap(shifted_w_.data(), shifted_w_.size()), p.mu);
    inner_.settings() = settings_.inner;
    inner_.compute(*subproblem_);
    q_norm_ = inner_.free_velocity_norm();  // w' = w so far: the original ||q||
    error_.emplace(p, q_norm_);
    const Index m = p.size(), n = p.num_dofs();
    for (Vector* x : {&r_, &trial_r_, &best_r_}) x->resize(m);
    for (Vector* x : {&v_, &trial_v_, &best_v_}) x->resize(n);
    info_ = SolverInfo();
    info_.setup_seconds = clock.seconds();
    return *this;
  }

  /// r: warm start in, solution out (the best iterate if the solve fails);
  /// v: out, starting from M^-1 (H r + f) (as GlobalNewton's solve).
  const SolverInfo& solve(Eigen::Ref<Vector> r, Eigen::Ref<Vector> v) {
    fcsolve::check_solve_arguments("ProximalPointGlobal", problem_.has_value(), r,
                                   problem_ ? problem_->size() : 0, v,
                                   problem_ ? problem_->num_dofs() : 0, "v");
    Stopwatch clock;
    r_ = r;
    v_ = inner_.velocity(r_);
    double error = (*error_)(r_, v_);
    best_r_ = r_;
    best_v_ = v_;
    if (this->run(error, clock) != Status::Converged) {
      r_ = best_r_;
      v_ = best_v_;
    }
    r = r_;
    v = v_;
    info_.solve_seconds = clock.seconds();
    return info_;
  }

  /// ||H^T M^-1 f + w||, the FCLIB error scale, known since compute().
  double free_velocity_norm() const { return q_norm_; }

 private:
  // ---- hooks of ProximalPointLoop
  double alpha_unit() const {
    const double mean = inner_.lumped_diagonal_mean();
    return mean > 0 && std::isfinite(mean) ? mean : 1.0;
  }
  double outer_scale() const { return error_->scale(); }
  Index num_contacts() const { return problem_->num_contacts(); }
  double pose_subproblem(double alpha) {
    FCSOLVE_NO_MALLOC_BEGIN();
    shifted_w_ = problem_->w - alpha * r_;
    FCSOLVE_NO_MALLOC_END();
    inner_.set_compliance(alpha);
    return error_scale(inner_.free_velocity_norm());
  }
  const SolverInfo& solve_subproblem() {
    trial_r_ = r_;
    return inner_.solve(trial_r_, trial_v_);
  }
  double trial_error() { return (*error_)(trial_r_, trial_v_); }
  void take_trial() {
    r_ = trial_r_;
    v_ = trial_v_;
  }
  void save_best() {
    best_r_ = r_;
    best_v_ = v_;
  }

  std::optional<GlobalProblemView> problem_, subproblem_;
  std::optional<GlobalErrorEvaluator<Cone>> error_;
  Vector shifted_w_, r_, trial_r_, best_r_, v_, trial_v_, best_v_;
  double q_norm_ = 0;
};

}  // namespace fcsolve
