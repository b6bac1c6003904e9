// Semismooth Newton on the global problem FC/I(M, H, f, w, mu) in the
// unknowns (v, r), without forming W = H^T M^-1 H:
//   M v - H r - f = 0,   G(r, u) = 0,   u = H^T v + w,
//   [ M      -H     ] [dv]     [ M v - H r - f ]
//   [ A H^T   B + dI] [dr] = - [ G             ]
// (global_jacobian.hpp; d: the Levenberg-Marquardt-like shift of
// newton_step.hpp). The step keeps M v = H r + f, so the line search works on
// psi = 1/2 ||G||^2 alone, along (v + t dv, r + t dr). M is factorised once
// (GlobalReduction, without W) for the starting v = M^-1 (H r + f) and the
// error scale ||H^T M^-1 f + w||. The rho strategies use the lumped
// approximation W^aa ~ H_a^T diag(M)^-1 H_a. There is no hybrid fallback in
// this form (its sweeps need W); bilateral constraints (G, b) are not
// supported here: use the reduced form (Newton) for them.
#pragma once

#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/linalg/default_backend.hpp>
#include <fcsolve/newton/contact_newton.hpp>
#include <fcsolve/newton/global_jacobian.hpp>
#include <fcsolve/newton/linear_solvers.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/problem/reduction.hpp>
#include <fcsolve/problem/validate.hpp>

#include <algorithm>
#include <optional>
#include <string>
#include <type_traits>

namespace fcsolve {

template <template <class> class Formulation, class Cone,
          class LinearSolver = SparseNewtonLinearSolver<DefaultBackend>, class Backend = DefaultBackend>
class GlobalNewton
    : public ContactNewton<GlobalNewton<Formulation, Cone, LinearSolver, Backend>, Formulation, Cone> {
  using Base = ContactNewton<GlobalNewton, Formulation, Cone>;
  friend NewtonLoop<GlobalNewton>;
  friend Base;  // calls update_velocity()
  using Base::r_, Base::u_, Base::best_r_, Base::residual_, Base::psi_, Base::scale_, Base::reference_norm_;
  using Base::counters_, Base::info_, Base::settings_;

 public:
  using Base::d;
  static_assert(std::is_same_v<typename LinearSolver::Matrix, SparseMatrix>,
                "the global Newton system is sparse: use a sparse linear solver");

  explicit GlobalNewton(const NewtonSettings& s = {}) : Base(s) {}

  /// Validates, factorises M, fixes the pattern of the Newton matrix. The
  /// viewed data must outlive the solver. Throws InvalidProblem for bad data
  /// or a singular M, UsageError for bilateral constraints.
  GlobalNewton& compute(const GlobalProblemView& p) {
    Stopwatch clock;
    validate(p);
    this->check_dimension(p.d, d);
    if (p.has_bilateral())
      throw UsageError("GlobalNewton does not handle bilateral constraints (G, b): use the reduced form");
    problem_.emplace(p);
    reduction_.compute(p, /*form_W=*/false);
    jacobian_.compute(p.M, p.H);
    system_.compute(jacobian_);
    const Vector lumped = lumped_inverse_mass(p.M);
    const SparseMatrix H(p.H);
    residual_.compute(p.mu, settings_.rho_strategy, settings_.rho, [&](Index a) {
      const SparseMatrix Ha = H.middleCols(a * d, d);
      const SparseMatrix Wa = Ha.transpose() * lumped.asDiagonal() * Ha;
      return SmallMatrix<d>(Wa.toDense());
    });
    const Index n = p.num_dofs(), m = p.size();
    for (Vector* x : {&r_, &u_, &best_r_, &Hdv_}) x->resize(m);
    for (Vector* x : {&v_, &best_v_, &Mv_, &Hr_}) x->resize(n);
    F_.resize(n + m);
    dz_.resize(n + m);
    q_norm_ = reduction_.free_velocity_norm();
    scale_ = error_scale(q_norm_);
    f_norm_ = p.f.norm();
    reference_norm_ = residual_.reference_norm(reduction_.local().q);  // q = H^T M^-1 f + w
    info_ = SolverInfo();
    info_.setup_seconds = clock.seconds();
    return *this;
  }

  /// r: warm start in, solution out (the best iterate if the solve fails);
  /// v: out, starting from M^-1 (H r + f).
  const SolverInfo& solve(Eigen::Ref<Vector> r, Eigen::Ref<Vector> v) {
    fcsolve::check_solve_arguments("GlobalNewton", problem_.has_value(), r, problem_ ? problem_->size() : 0,
                          v, problem_ ? problem_->num_dofs() : 0, "v");
    Stopwatch clock;
    r_ = r;
    v_ = reduction_.velocity(r_);
    update_velocity();
    this->run(clock);
    r = r_;
    v = v_;
    info_.solve_seconds = clock.seconds();
    return info_;
  }

  /// ||H^T M^-1 f + w||, the FCLIB error scale, known since compute().
  double free_velocity_norm() const { return q_norm_; }

  /// The complementarity and equilibrium parts of the error of the last solve.
  double complementarity() const { return complementarity_; }
  double equilibrium() const { return equilibrium_; }

 private:
  static Vector lumped_inverse_mass(const SparseMap& M) {
    Vector dinv = SparseMatrix(M).diagonal().cwiseAbs();
    const double fallback = dinv.maxCoeff() > 0 ? dinv.maxCoeff() : 1.0;
    for (Index i = 0; i < dinv.size(); ++i) dinv[i] = 1.0 / (dinv[i] > 0 ? dinv[i] : fallback);
    return dinv;
  }

  // ---- hooks of NewtonLoop (refresh, set_rho_factor: ContactNewton)
  /// max(complementarity, equilibrium), as core/error.hpp's global error.
  double error() {
    const GlobalProblemView& p = *problem_;
    complementarity_ = std::sqrt(natural_map_norms<Cone>(r_, u_, p.mu).squared_sum) / scale_;
    residual_equilibrium();
    const double denom = std::max({f_norm_, Mv_.norm(), Hr_.norm()});
    equilibrium_ = F_.head(p.num_dofs()).norm() / (denom > 0 ? denom : 1.0);
    return std::max(complementarity_, equilibrium_);
  }
  void save_best() {
    best_r_ = r_;
    best_v_ = v_;
  }
  void restore_best() {
    r_ = best_r_;
    v_ = best_v_;
    update_velocity();
  }
  bool fallback_sweep() { return false; }

  /// One globalised Newton step; false when no step could be taken. Only
  /// the factorisation (in system_.solve) may allocate.
  bool newton_step() {
    const Index n = problem_->num_dofs();
    FCSOLVE_NO_MALLOC_BEGIN();
    jacobian_.assemble(residual_.A(), residual_.B(), system_.matrix());
    residual_equilibrium();  // F = (M v - H r - f, G)
    F_.tail(F_.size() - n) = residual_.G();
    FCSOLVE_NO_MALLOC_END();
    if (!system_.solve(F_, dz_, this->shift(psi_, reference_norm_),
                       settings_.singular_regularization, counters_))
      return false;
    FCSOLVE_NO_MALLOC_BEGIN();
    Hdv_.noalias() = problem_->H.transpose() * dz_.head(n);
    const auto dr = dz_.tail(dz_.size() - n);
    const bool stepped = this->take_step([&](double s) { return residual_.trial(r_, dr, u_, Hdv_, s); },
                                         [&](double t) {
                                           v_ += t * dz_.head(n);
                                           r_ += t * dr;
                                         });
    FCSOLVE_NO_MALLOC_END();
    return stepped;
  }

  void update_velocity() {
    u_.noalias() = problem_->H.transpose() * v_;
    u_ += problem_->w;
  }
  /// F.head(n) = M v - H r - f, with M v and H r kept for the error's scale.
  void residual_equilibrium() {
    const GlobalProblemView& p = *problem_;
    Mv_.noalias() = p.M * v_;
    Hr_.noalias() = p.H * r_;
    F_.head(p.num_dofs()) = Mv_ - Hr_ - p.f;
  }

  std::optional<GlobalProblemView> problem_;
  GlobalReduction<Backend> reduction_;
  GlobalJacobian<d> jacobian_;
  RegularisedNewtonSystem<LinearSolver, GlobalJacobian<d>> system_;  // points to jacobian_
  Vector v_, best_v_, Hdv_, Mv_, Hr_, F_, dz_;
  double q_norm_ = 0, f_norm_ = 0;
  double complementarity_ = 0, equilibrium_ = 0;
};

}  // namespace fcsolve
