// ADMM on the global problem FC/I(M, H, f, w, mu), in (v, r), W never formed
// (Acary, Bremond & Huber 2018, sec. on ADMM; Boyd et al. 2011, sec. 3.1;
// docs/references.md). For a fixed De Saxce shift s (s^a = (mu^a ||u_T^a||,
// 0, 0), u = H^T v + w) FC/I is the optimality system of the convex QP
//   min 1/2 v^T M v - f^T v   s.t.   xi = H^T v + w + s,  xi in K*,
// whose multiplier of the equality is r in K (M v = H r + f, K* ∋ xi ⊥ r).
// ADMM on its augmented Lagrangian, with s updated at every iterate so that
// the fixed points solve the Coulomb problem, not its convex relaxation:
//   (M + rho H H^T) v = f + H (rh + rho (xih - w - s))        (v-update)
//   x   = alpha (H^T v + w + s) + (1 - alpha) xih             (over-relaxation)
//   r   = P_K(rh - rho x),   xi = x - (rh - r) / rho          (xi- and r-update)
//   s   = g(H^T v + w)                                         (De Saxce's shift)
// The r-update is the xi-step xi = P_{K*}(x - rh / rho) and the dual step
// r = rh - rho (x - xi) written through Moreau's decomposition
// P_{K*}(y) = y + P_K(-y). After it, M v - H r - f = rho H (xih - xi): the
// balance holds up to the dual residual, and the FCLIB error measures both.
// (xih, rh) = (xi, r) without acceleration; with it, Nesterov's extrapolation
// with restart (admm_rules.hpp).
// rho is a compliance's inverse (force / velocity), 1 / rho of the reduced
// ADMM (admm_solver.hpp): rho0 = settings.rho / mean diag(H^T diag(M)^-1 H),
// the lumped W_ii (O(nnz H)), adapted by residual balancing or the OSQP rule;
// a new rho refactorises M + rho H H^T (numerically only). M itself is
// factorised on the same pattern (rho = 0) for the error scale ||H^T M^-1 f
// + w|| and the velocity that balances r, M^-1 (H r + f), at the start and
// the end of a solve: one factor in memory (what 10^5 elastic contacts need,
// docs/results.md).
// The returned (r, v) is the iterate of least FCLIB error (problem/error.hpp).
#pragma once

#include <fcsolve/admm/admm_global_factorization.hpp>
#include <fcsolve/admm/admm_loop.hpp>
#include <fcsolve/admm/admm_rules.hpp>
#include <fcsolve/admm/admm_settings.hpp>
#include <fcsolve/core/exceptions.hpp>
#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/core/timer.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/problem/global_problem.hpp>
#include <fcsolve/problem/symmetry.hpp>
#include <fcsolve/problem/validate.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace fcsolve {

template <class Cone, class Backend = DefaultBackend>
class AdmmGlobal : public AdmmLoop<AdmmGlobal<Cone, Backend>> {
  using Base = AdmmLoop<AdmmGlobal>;
  friend Base;
  using Base::best_error_, Base::factorization_ok_, Base::factorizations_, Base::info_, Base::rho0_,
      Base::rho_, Base::settings_;

 public:
  static constexpr int d = Cone::dim;
  using Settings = AdmmSettings;
  using Vec = typename Cone::Vec;

  explicit AdmmGlobal(const Settings& s = {}) : Base(s) {}
  /// ||H^T M^-1 f + w||, the FCLIB error scale, known since compute().
  double free_velocity_norm() const { return q_norm_; }

  /// Validates p, analyses the pattern of M + H H^T once and factorises M
  /// (the error scale, ||H^T M^-1 f + w||, and the starting velocity). The
  /// viewed data must outlive the solver. Throws InvalidProblem for bad
  /// data or a singular M, UsageError for bilateral constraints or the
  /// spectral rho0 (FC/II only).
  AdmmGlobal& compute(const GlobalProblemView& p) {
    Stopwatch clock;
    if (p.has_bilateral())
      throw UsageError("AdmmGlobal does not handle bilateral constraints (G, b): use Admm");
    if (settings_.rho_init == AdmmRhoInit::Spectral)
      throw UsageError("AdmmGlobal: the spectral rho0 needs W; use rho_init = given");
    if (!(settings_.relaxation > 0 && settings_.relaxation < 2))
      throw UsageError("AdmmGlobal: relaxation must lie in (0, 2)");
    problem_.emplace(validated(p, d));
    factorize_mass(p);
    for (Vector* x : {&r_, &rh_, &r_prev_, &xi_, &xih_, &xi_prev_, &s_, &u_, &best_r_, &t_})
      x->setZero(p.size());
    for (Vector* x : {&v_, &b_, &best_v_}) x->setZero(p.num_dofs());
    factorization_.solve(Vector(p.f), free_velocity_);
    q_norm_ = (p.H.transpose() * free_velocity_ + p.w).norm();
    error_.emplace(p, q_norm_);
    rho0_ = settings_.rho / lumped_delassus_mean(p);
    info_ = SolverInfo();
    info_.setup_seconds = clock.seconds();
    return *this;
  }

  /// r: warm start in, solution out (the best iterate); v: out, the best
  /// iterate's velocity (M^-1 (H r + f) at the start).
  const SolverInfo& solve(Eigen::Ref<Vector> r, Eigen::Ref<Vector> v) {
    fcsolve::check_solve_arguments("AdmmGlobal", problem_.has_value(), r, size(), v,
                                   problem_ ? problem_->num_dofs() : 0, "v");
    Stopwatch clock;
    r_ = r;
    balanced_velocity(r_, v_);
    this->begin_solve();  // the factor of M + rho0 H H^T
    update_u();
    const double error = shift_and_error();
    // xi starts as u + s projected on K*: the slack the warm start implies
    for (Index c = 0; c < problem_->num_contacts(); ++c)
      xi_.template segment<d>(c * d) = Cone::project_dual(
          Vec(u_.template segment<d>(c * d) + s_.template segment<d>(c * d)), problem_->mu[c]);
    this->run(error, clock);
    r = best_r_;
    v = best_v_;
    return info_;
  }

 private:
  // ---- hooks of AdmmLoop
  static constexpr const char* kFactorizationFailure = "M + rho H H^T could not be factorised";
  double step(double& primal_sq, double& dual_sq) {
    update_v();
    update_u();
    update_xi_and_r(primal_sq, dual_sq);  // with the shift of the last iterate
    return shift_and_error();
  }
  void save_best() {
    best_r_ = r_;
    best_v_ = v_;
  }
  /// In velocity units: r / rho is the scaled dual variable.
  double combined_residual(double dual_sq) const {
    return dual_sq + (r_ - rh_).squaredNorm() / (rho_ * rho_);
  }
  AdmmPoint point() { return {&xi_, &xih_, &xi_prev_, &r_, &rh_, &r_prev_}; }
  bool factorize(double rho) { return factorization_.factorize(rho); }
  /// The best r with the velocity that balances it, v = M^-1 (H r + f),
  /// when that is no worse: ADMM's own v balances r only up to the dual
  /// residual, which can leave the best iterate above tol. Not when the
  /// best iterate already meets tol: its own v balances r to tol, and M's
  /// refactorisation costs as much as 30 to 40 iterations on large elastic
  /// bodies (18-27 s of 115-145 at 10^5 contacts, docs/results.md). A
  /// restart balances its r itself (solve()).
  void finish_solve() {
    if (best_error_ <= settings_.tol || !balanced_velocity(best_r_, v_)) return;
    r_ = best_r_;
    update_u();
    const double error = shift_and_error();
    if (error <= best_error_) {
      best_error_ = error;
      best_v_ = v_;
    }
  }

  /// (M + rho H H^T) v = f + H (rh + rho (xih - w - s)); the solve may
  /// allocate (CHOLMOD, UMFPACK): it runs outside the no-allocation bracket.
  void update_v() {
    t_ = rh_ + rho_ * (xih_ - problem_->w - s_);
    b_.noalias() = problem_->H * t_;
    b_ += problem_->f;
    FCSOLVE_NO_MALLOC_END();
    factorization_.solve(b_, v_);
    FCSOLVE_NO_MALLOC_BEGIN();
  }

  /// Over-relaxation, r = P_K(rh - rho x), xi = x - (rh - r) / rho; the
  /// squared primal (x - xi) and dual (xi - xih) residuals, both velocities.
  void update_xi_and_r(double& primal_sq, double& dual_sq) {
    const double alpha = settings_.relaxation;
    const VectorMap& mu = problem_->mu;
    r_prev_ = r_;
    xi_prev_ = xi_;
    for (Index c = 0; c < problem_->num_contacts(); ++c) {
      const Vec x = alpha * (u_.template segment<d>(c * d) + s_.template segment<d>(c * d)) +
                    (1 - alpha) * xih_.template segment<d>(c * d);
      const Vec rhc = rh_.template segment<d>(c * d);
      const Vec rc = Cone::project(Vec(rhc - rho_ * x), mu[c]);
      const Vec xic = x - (rhc - rc) / rho_;
      r_.template segment<d>(c * d) = rc;
      xi_.template segment<d>(c * d) = xic;
      primal_sq += (x - xic).squaredNorm();
      dual_sq += (xic - xih_.template segment<d>(c * d)).squaredNorm();
    }
  }

  /// u_ = H^T v + w.
  void update_u() {
    u_.noalias() = problem_->H.transpose() * v_;
    u_ += problem_->w;
  }

  /// s_ = g(u_); returns the FCLIB error of (r_, v_) (u_ up to date).
  double shift_and_error() {
    for (Index c = 0; c < problem_->num_contacts(); ++c)
      s_.template segment<d>(c * d) = Cone::de_saxce_shift(Vec(u_.template segment<d>(c * d)), problem_->mu[c]);
    return (*error_)(r_, u_, v_);
  }

  /// One factor in memory, M's or M + rho H H^T's, on one pattern: the
  /// symbolic analysis once, a numerical factorisation per switch. rho_ = 0
  /// while it holds M. Cholesky when M is symmetric up to rounding (LU if
  /// that fails, as problem/reduction.hpp), LU otherwise.
  void factorize_mass(const GlobalProblemView& p) {
    const bool symmetric = relative_asymmetry(p.M) <= kSymmetryRoundoff;
    factorization_.compute(p.M, p.H, symmetric);
    bool ok = factorization_.factorize(0);
    if (!ok && symmetric) {
      factorization_.compute(p.M, p.H, false);
      ok = factorization_.factorize(0);
    }
    if (!ok) throw InvalidProblem("M", "singular or ill-formed M: its factorisation failed");
    rho_ = 0;
    factorization_ok_ = true;
  }

  /// v = M^-1 (H r + f), M factorised again if the factor holds another
  /// rho; false if that failed.
  bool balanced_velocity(const Vector& r, Vector& v) {
    if (r.isZero(0.0)) {
      v = free_velocity_;  // M^-1 f, from compute()
      return true;
    }
    if (rho_ != 0) {
      if (!factorization_.factorize(0)) return false;
      rho_ = 0;
    }
    b_.noalias() = problem_->H * r;
    b_ += problem_->f;
    factorization_.solve(b_, v);
    return true;
  }

  /// Relative residuals: primal ||x - xi|| / max(||u + s||, ||xi||), dual
  /// rho ||xi - xih|| / max(||r||, ||w||) (velocity times rho: a force).
  bool adapt_rho(double primal_sq, double dual_sq) {
    if (factorizations_ > settings_.max_refactorizations) return false;
    const double tiny = std::numeric_limits<double>::min();
    const double rp = std::sqrt(primal_sq) / std::max({(u_ + s_).norm(), xi_.norm(), tiny});
    const double rd = rho_ * std::sqrt(dual_sq) / std::max({r_.norm(), rho_ * problem_->w.norm(), tiny});
    const double factor = admm_rho_factor(settings_.rho_strategy, rp, rd);
    if (factor == 1) return false;
    const double old = rho_;
    factorization_ok_ = this->refactorize(rho_ * factor);
    if (!factorization_ok_) factorization_ok_ = this->refactorize(old);
    return true;
  }

  /// mean over the contact unknowns of (H^T diag(M)^-1 H)_ii, 1 if not positive.
  static double lumped_delassus_mean(const GlobalProblemView& p) {
    const Vector diagonal = SparseMatrix(p.M).diagonal();
    double sum = 0;
    for (Index j = 0; j < p.H.outerSize(); ++j)
      for (SparseMap::InnerIterator it(p.H, j); it; ++it)
        if (diagonal[it.row()] > 0) sum += it.value() * it.value() / diagonal[it.row()];
    const double mean = p.size() > 0 ? sum / double(p.size()) : 0.0;
    return mean > 0 && std::isfinite(mean) ? mean : 1.0;
  }

  Index size() const { return problem_ ? problem_->size() : 0; }

  std::optional<GlobalProblemView> problem_;
  std::optional<GlobalErrorEvaluator<Cone>> error_;
  GlobalAdmmFactorization<Backend> factorization_;
  Vector r_, rh_, r_prev_, xi_, xih_, xi_prev_, s_, u_, best_r_, t_;
  Vector v_, b_, best_v_, free_velocity_;
  double q_norm_ = 0;
};

}  // namespace fcsolve
