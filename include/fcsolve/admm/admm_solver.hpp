// ADMM on FC/II (Acary, Bremond & Huber 2018, sec. on ADMM; Boyd et al. 2011;
// docs/references.md). FC/II is the VI  -(W r + q + s(r)) in N_K(r) with De
// Saxce's shift s(r)^a = (mu^a ||u_T^a||, 0, 0), u = W r + q. For a fixed s it
// is the first-order condition of the convex QP
//   min 1/2 r^T W r + (q + s)^T r   s.t.  r = z,  z in K,
// and ADMM on that QP with s updated at every iterate solves the Coulomb
// problem itself, not its convex relaxation (s = 0). Scaled form (xi = y/rho):
//   r   = (W_s + rho I)^-1 ( rho (zh - xih) - q - s - W_a r_prev )  (r-update)
//   rr  = alpha r + (1 - alpha) zh                                   (over-relaxation)
//   z   = P_K(rr + xih),   xi = xih + rr - z                         (projection, dual step)
//   s   = g(W r + q)                                                  (De Saxce's shift)
// W_s = (W + W^T)/2 is factorised (W of real data is symmetric only up to
// rounding); its antisymmetric rest W_a = (W - W^T)/2 is lagged on the
// right-hand side at the last r, so that a fixed point (r = z) satisfies
// W z + q + s = -rho xi, xi in N_K(z): it solves FC/II with the real W.
// The shift is taken at r, as Siconos' ADMM does: taken at z instead (same
// fixed points) it needed 100 times more iterations on BoxesStack1 and
// Capsules-i97-269 (docs/results.md).
// (zh, xih) = (z, xi) without acceleration; with it, Nesterov's extrapolation
// with restart of Goldstein, O'Donoghue, Setzer & Baraniuk 2014 (alg. 8).
// rho: a spectral rho0 = sqrt(L m) (L/m)^0.2 (sqrt(L m) is the optimal rho of
// Ghadimi et al. 2015 for QPs; the power 0.2 leans it towards L), adapted by
// residual balancing (Boyd et al. 2011, eq. 3.13) or the OSQP rule (Stellato
// et al. 2020, sec. 5.2); a new rho refactorises W_s + rho I (outside the
// no-allocation bracket) and rescales xi = y / rho.
// The returned r is the iterate r of least FCLIB error: u = W r + q is
// computed for the shift anyway, so the error costs one projection per
// contact and is evaluated every iteration; the ADMM residuals only steer rho
// and the restart, never convergence.
#pragma once

#include <fcsolve/admm/admm_factorization.hpp>
#include <fcsolve/admm/admm_loop.hpp>
#include <fcsolve/admm/admm_rules.hpp>
#include <fcsolve/admm/admm_settings.hpp>
#include <fcsolve/core/exceptions.hpp>
#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/core/timer.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/problem/local_problem.hpp>
#include <fcsolve/problem/validate.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace fcsolve {

template <class Cone, class Storage, class Factorization = DefaultAdmmFactorization<Storage>>
class Admm : public AdmmLoop<Admm<Cone, Storage, Factorization>> {
  using Base = AdmmLoop<Admm>;
  friend Base;
  using Base::best_error_, Base::factorization_ok_, Base::factorizations_, Base::info_, Base::rho0_,
      Base::rho_, Base::settings_;

 public:
  static constexpr int d = Cone::dim;
  using Settings = AdmmSettings;
  using Vec = typename Cone::Vec;

  explicit Admm(const Settings& s = {}) : Base(s) {}

  /// Validates p, splits W into its symmetric and antisymmetric parts,
  /// estimates rho0 and factorises W_s + rho0 I. p must outlive *this.
  Admm& compute(const LocalProblemView& p) {
    Stopwatch clock;
    if (!(settings_.relaxation > 0 && settings_.relaxation < 2))
      throw UsageError("Admm: relaxation must lie in (0, 2)");
    problem_.emplace(validated(p, d));
    W_.compute(p.W);
    const Index m = p.size();
    const SparseMatrix W(p.W), Wt(p.W.transpose());
    const SparseMatrix Ws = 0.5 * (W + Wt);
    Wa_ = 0.5 * (W - Wt);
    Wa_.prune(0.0);
    Wa_.makeCompressed();
    factorization_.compute(Ws);
    for (Vector* v : {&r_, &z_, &xi_, &zh_, &xih_, &z_prev_, &xi_prev_, &b_, &u_, &s_, &best_r_,
                      &best_u_})
      v->setZero(m);
    scale_ = error_scale(p.q.norm());
    rho0_ = initial_rho(Ws);
    info_ = SolverInfo();
    factorizations_ = 0;
    rho_floor_ = 0;
    factorization_ok_ = this->refactorize(rho0_);
    // W_s + rho0 I indefinite (W_s is semidefinite only up to rounding):
    // a larger rho0, up to 1e6 times
    for (int i = 0; i < 6 && !factorization_ok_; ++i) {
      rho0_ *= 10;
      rho_floor_ = rho0_;
      factorization_ok_ = this->refactorize(rho0_);
    }
    info_.setup_seconds = clock.seconds();
    return *this;
  }

  /// r: warm start in (z = r, xi = 0), solution out; u = W r + q on return.
  const SolverInfo& solve(Eigen::Ref<Vector> r, Eigen::Ref<Vector> u) {
    Stopwatch clock;
    fcsolve::check_solve_arguments("Admm", problem_.has_value(), r, size(), u, size(), "u");
    this->begin_solve();
    z_ = r;
    r_ = r;
    xi_.setZero();
    const double error = velocity_and_error();  // u_, s_ at r_
    this->run(error, clock);
    r = best_r_;
    u = best_u_;
    return info_;
  }

 private:
  Index size() const { return problem_ ? problem_->size() : 0; }

  // ---- hooks of AdmmLoop
  static constexpr const char* kFactorizationFailure = "W_s + rho I is not positive definite";
  double step(double& primal_sq, double& dual_sq) {
    update_r();
    project_and_update_dual(primal_sq, dual_sq);
    return velocity_and_error();
  }
  void save_best() {
    best_r_ = r_;
    best_u_ = u_;
  }
  double combined_residual(double dual_sq) const { return (xi_ - xih_).squaredNorm() + dual_sq; }
  AdmmPoint point() { return {&z_, &zh_, &z_prev_, &xi_, &xih_, &xi_prev_}; }
  bool factorize(double rho) { return factorization_.factorize(rho); }
  void finish_solve() {}

  /// r-update: (W_s + rho I) r = rho (zh - xih) - q - s - W_a r. Called with
  /// allocation forbidden; a factorisation whose solve allocates is let.
  void update_r() {
    b_ = rho_ * (zh_ - xih_) - problem_->q - s_;
    if (Wa_.nonZeros() > 0) b_.noalias() -= Wa_ * r_;
    if constexpr (Factorization::solve_allocates) FCSOLVE_NO_MALLOC_END();
    factorization_.solve(b_, r_);
    if constexpr (Factorization::solve_allocates) FCSOLVE_NO_MALLOC_BEGIN();
  }

  /// Over-relaxation, projection onto K, dual step; the squared primal
  /// (r - z) and dual (z - zh) residuals.
  void project_and_update_dual(double& primal_sq, double& dual_sq) {
    const double alpha = settings_.relaxation;
    z_prev_ = z_;
    xi_prev_ = xi_;
    const LocalProblemView& p = *problem_;
    for (Index c = 0; c < p.num_contacts(); ++c) {
      const Vec rr = alpha * r_.template segment<d>(c * d) + (1 - alpha) * zh_.template segment<d>(c * d);
      const Vec v = rr + xih_.template segment<d>(c * d);
      const Vec zc = Cone::project(v, p.mu[c]);
      z_.template segment<d>(c * d) = zc;
      xi_.template segment<d>(c * d) = v - zc;
      primal_sq += (r_.template segment<d>(c * d) - zc).squaredNorm();
      dual_sq += (zc - zh_.template segment<d>(c * d)).squaredNorm();
    }
  }

  /// u_ = W r + q, s_ = g(u_); returns the FCLIB error of r_.
  double velocity_and_error() {
    const LocalProblemView& p = *problem_;
    W_.multiply(r_, u_);
    u_ += p.q;
    double sq = 0;
    for (Index c = 0; c < p.num_contacts(); ++c) {
      const Vec uc = u_.template segment<d>(c * d), rc = r_.template segment<d>(c * d);
      const Vec shift = Cone::de_saxce_shift(uc, p.mu[c]);
      s_.template segment<d>(c * d) = shift;
      sq += (rc - Cone::project(Vec(rc - uc - shift), p.mu[c])).squaredNorm();
    }
    return std::sqrt(sq) / scale_;
  }

  /// New rho from the relative residuals (OSQP's scaling: r_p / max(||r||,
  /// ||z||), r_d / max(||y||, ||q||) with y = rho xi); true if it changed
  /// (then W_s + rho I is refactorised and xi rescaled).
  bool adapt_rho(double primal_sq, double dual_sq) {
    if (factorizations_ > settings_.max_refactorizations) return false;
    const double tiny = std::numeric_limits<double>::min();
    const double rp = std::sqrt(primal_sq) / std::max({r_.norm(), z_.norm(), tiny});
    const double rd = rho_ * std::sqrt(dual_sq) / std::max({rho_ * xi_.norm(), problem_->q.norm(), tiny});
    const double factor = admm_rho_factor(settings_.rho_strategy, rp, rd);
    if (factor < 1 && rho_ * factor < rho_floor_) return false;
    if (factor == 1) return false;
    const double old = rho_;
    factorization_ok_ = this->refactorize(rho_ * factor);
    if (!factorization_ok_ && factor < 1) {
      // W_s is positive semidefinite only up to rounding: a small rho can
      // leave W_s + rho I indefinite. Keep the last rho and go no lower.
      rho_floor_ = old;
      factorization_ok_ = this->refactorize(old);
    }
    xi_ *= old / rho_;
    return true;
  }

  /// rho0 (AdmmSettings::rho_init): L = lambda_max(W_s) by power iteration,
  /// m = the smallest positive W_ii (an upper bound of lambda_min that stays
  /// positive when W is rank-deficient, as W of piles is).
  double initial_rho(const SparseMatrix& Ws) const {
    if (settings_.rho_init == AdmmRhoInit::Given) return settings_.rho;
    const Index m = Ws.rows();
    Vector x = Vector::Ones(m) / std::sqrt(double(std::max<Index>(m, 1))), y(m);
    double L = 0;
    for (int i = 0; i < settings_.power_iterations; ++i) {
      y.noalias() = Ws * x;
      L = x.dot(y);
      const double n = y.norm();
      if (!(n > 0)) break;
      x = y / n;
    }
    double mmin = std::numeric_limits<double>::infinity();
    for (Index i = 0; i < m; ++i)
      if (Ws.coeff(i, i) > 0) mmin = std::min(mmin, Ws.coeff(i, i));
    if (!(L > 0) || !std::isfinite(mmin)) return settings_.rho;
    mmin = std::min(mmin, L);
    return settings_.rho * std::sqrt(L * mmin) * std::pow(L / mmin, 0.2);
  }

  std::optional<LocalProblemView> problem_;
  Storage W_;
  SparseMatrix Wa_;
  Factorization factorization_;
  Vector r_, z_, xi_, zh_, xih_, z_prev_, xi_prev_, b_, u_, s_, best_r_, best_u_;
  double scale_ = 1, rho_floor_ = 0;
};

}  // namespace fcsolve
