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
//
// An optional contact compliance c >= 0 (set_compliance; 0 by default, and
// then nothing changes, at no cost) makes u = H^T v + w + c r: the proximal
// subproblem FC/II(W + c I, ...) of ppa/proximal_point_global.hpp without W.
// The r-block of the Newton matrix becomes B + c A (dG/dr = A du/dr + B),
// the step's du = H^T dv + c dr, and the rho strategies see W^aa + c I.
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
#include <cmath>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace fcsolve {

template <template <class> class Formulation, class Cone,
          class LinearSolver = SparseNewtonLinearSolver<DefaultBackend>, class Backend = DefaultBackend>
class GlobalNewton
    : public ContactNewton<GlobalNewton<Formulation, Cone, LinearSolver, Backend>, Formulation, Cone> {
  using Base = ContactNewton<GlobalNewton, Formulation, Cone>;
  friend NewtonLoop<GlobalNewton>;
  friend Base;  // calls update_velocity()
  using Base::r_, Base::u_, Base::best_r_, Base::residual_, Base::psi_, Base::reference_norm_;
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
    this->forget_step_time();
    lumped_blocks_.resize(std::size_t(p.num_contacts()));
    const Vector lumped = lumped_inverse_mass(p.M);
    for (Index a = 0; a < p.num_contacts(); ++a) lumped_blocks_[std::size_t(a)] = lumped_block(p.H, lumped, a);
    const Index n = p.num_dofs(), m = p.size();
    for (Vector* x : {&r_, &u_, &best_r_, &du_}) x->resize(m);
    for (Vector* x : {&v_, &best_v_}) x->resize(n);
    F_.resize(n + m);
    dz_.resize(n + m);
    free_velocity_ = reduction_.local().q;  // q = H^T M^-1 f + w
    forced_velocity_ = free_velocity_ - p.w;
    error_.emplace(p, reduction_.free_velocity_norm());
    compliance_ = 0;
    update_contact_terms();
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

  /// The contact compliance c >= 0 of u = H^T v + w + c r (0 after
  /// compute()). It also rereads w from the viewed data: a caller that
  /// rewrote w in place (the proximal subproblem's w - c r_k) calls it
  /// after. O(nnz(H)), no factorisation; rho and the error scale follow.
  GlobalNewton& set_compliance(double c) {
    if (!problem_) throw UsageError("GlobalNewton: set_compliance() before compute()");
    if (!(c >= 0) || !std::isfinite(c)) throw UsageError("GlobalNewton: the compliance must be finite and >= 0");
    compliance_ = c;
    free_velocity_ = forced_velocity_ + problem_->w;
    update_contact_terms();
    return *this;
  }
  double compliance() const { return compliance_; }

  /// v = M^-1 (H r + f), by the factorisation of compute().
  Vector velocity(const Eigen::Ref<const Vector>& r) const { return reduction_.velocity(r); }

  /// ||H^T M^-1 f + w||, the FCLIB error scale, known since compute()
  /// (with the w of the last set_compliance()).
  double free_velocity_norm() const { return q_norm_; }
  /// mean diag(H^T diag(M)^-1 H): the lumped W^aa of the rho strategies,
  /// averaged; O(nnz(H)) where mean diag(W) would need M^-1 H.
  double lumped_diagonal_mean() const {
    double sum = 0;
    for (const SmallMatrix<d>& Wa : lumped_blocks_) sum += Wa.diagonal().cwiseAbs().sum();
    return lumped_blocks_.empty() ? 0.0 : sum / double(d * lumped_blocks_.size());
  }

  /// The complementarity and equilibrium parts of the error of the last solve.
  double complementarity() const { return error_->complementarity(); }
  double equilibrium() const { return error_->equilibrium(); }

 private:
  static Vector lumped_inverse_mass(const SparseMap& M) {
    Vector dinv = SparseMatrix(M).diagonal().cwiseAbs();
    const double fallback = dinv.maxCoeff() > 0 ? dinv.maxCoeff() : 1.0;
    for (Index i = 0; i < dinv.size(); ++i) dinv[i] = 1.0 / (dinv[i] > 0 ? dinv[i] : fallback);
    return dinv;
  }

  /// Contact a's block H_a^T D H_a of the lumped W (D: the lumped M^-1),
  /// from the entries of H's columns a d .. a d + d - 1: a few dozen
  /// products a contact. (Formed as a sparse product of H.middleCols, each
  /// block had cost O(n) in Eigen's storage conversions: 31 of the 34 s of
  /// compute() on a sphere pile of 10^5 contacts, docs/results.md.)
  static SmallMatrix<d> lumped_block(const SparseMap& H, const Vector& lumped, Index a) {
    SmallMatrix<d> Wa;
    for (int i = 0; i < d; ++i)
      for (int j = 0; j <= i; ++j) {
        double sum = 0;
        for (SparseMap::InnerIterator hi(H, a * d + i); hi; ++hi)
          for (SparseMap::InnerIterator hj(H, a * d + j); hj; ++hj)
            if (hi.row() == hj.row()) sum += hi.value() * lumped[hi.row()] * hj.value();
        Wa(i, j) = Wa(j, i) = sum;
      }
    return Wa;
  }

  // ---- hooks of NewtonLoop (refresh, set_rho_factor: ContactNewton)
  /// rho (from W^aa ~ lumped block + c I), ||q|| and the error scale, and
  /// the reference ||G(0, q)|| of the shift, for the current w and c.
  void update_contact_terms() {
    residual_.compute(problem_->mu, settings_.rho_strategy, settings_.rho, [&](Index a) {
      SmallMatrix<d> Wa = lumped_blocks_[std::size_t(a)];
      if (compliance_ != 0) Wa.diagonal().array() += compliance_;
      return Wa;
    });
    q_norm_ = free_velocity_.norm();
    error_->set_scale(q_norm_);
    reference_norm_ = residual_.reference_norm(free_velocity_);
  }

  /// max(complementarity, equilibrium), as core/error.hpp's global error
  /// (with a compliance: that of the compliant problem).
  double error() { return (*error_)(r_, u_, v_); }
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
    jacobian_.assemble(residual_.A(), residual_.B(), system_.matrix(), compliance_);
    F_.head(n) = error_->balance_residual(r_, v_);  // F = (M v - H r - f, G)
    F_.tail(F_.size() - n) = residual_.G();
    FCSOLVE_NO_MALLOC_END();
    if (!system_.solve(F_, dz_, this->shift(psi_, reference_norm_),
                       settings_.singular_regularization, counters_))
      return false;
    FCSOLVE_NO_MALLOC_BEGIN();
    const auto dr = dz_.tail(dz_.size() - n);
    du_.noalias() = problem_->H.transpose() * dz_.head(n);
    if (compliance_ != 0) du_ += compliance_ * dr;
    const bool stepped = this->take_step([&](double s) { return residual_.trial(r_, dr, u_, du_, s); },
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
    if (compliance_ != 0) u_ += compliance_ * r_;
  }

  std::optional<GlobalProblemView> problem_;
  GlobalReduction<Backend> reduction_;
  GlobalJacobian<d> jacobian_;
  RegularisedNewtonSystem<LinearSolver, GlobalJacobian<d>> system_;  // points to jacobian_
  std::optional<GlobalErrorEvaluator<Cone>> error_;
  std::vector<SmallMatrix<d>, Eigen::aligned_allocator<SmallMatrix<d>>> lumped_blocks_;
  Vector free_velocity_, forced_velocity_;  // H^T M^-1 f + w and H^T M^-1 f
  Vector v_, best_v_, du_, F_, dz_;
  double q_norm_ = 0, compliance_ = 0;
};

}  // namespace fcsolve
