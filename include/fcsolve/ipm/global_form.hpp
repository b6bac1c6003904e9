// The global form of the interior-point Newton step, on FC/I(M, H, f, w, mu)
// without reduction. With r~p = r_p - E r_s (form_common.hpp), a Newton step
// (dv, dx, dy, ds) satisfies
//   M dv - Hs dy = -r_d,            Hs^T dv + E ds - dx = -r_p,
//   ds - n^T dx = -r_s,             T^-1 dx + T dy = xi   (NT-scaled o),
// hence dx = P (Hs^T dv + r~p) and the augmented system in (dv, dy)
//   [  M      -Hs       ] [dv]   [ -r_d            ]
//   [ -Hs^T   -P^-1 T^2 ] [dy] = [ r~p - P^-1 T xi ],   Hs = H D^-1,
// symmetric quasi-definite when s is frozen and M symmetric (LDL^T), LU
// otherwise. The augmented form is used rather than the Schur complement
// M + Hs T^-2 Hs^T, whose T^-2 blocks reach 1e16 x M for sticking contacts
// near the solution and make the product lose positive definiteness in
// floating point; here T^2 -> 0 for those contacts instead, and the static
// regularisation (+delta on M, -delta on the contact block, removed by
// iterative refinement) keeps K invertible when H is rank-deficient.
#pragma once

#include <fcsolve/core/exceptions.hpp>
#include <fcsolve/ipm/form_base.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/problem/global_problem.hpp>
#include <fcsolve/problem/reduction.hpp>
#include <fcsolve/problem/symmetry.hpp>

#include <algorithm>
#include <cmath>

namespace fcsolve {
namespace ipm {

template <class ConeType, class Factorization>
class GlobalForm : public FormBase<ConeType, Factorization, GlobalProblemView, -1> {
  using Base = FormBase<ConeType, Factorization, GlobalProblemView, -1>;
  using Base::m_, Base::nc_, Base::p_;

 public:
  using Base::D, Base::error_scale, Base::reaction;
  static constexpr bool is_global = true;

  /// Scales H, builds the augmented pattern, factorises M once (free
  /// velocity, the FCLIB error scale). Throws InvalidProblem if M is singular.
  void compute(const GlobalProblemView& p) {
    p_.emplace(p);
    n_ = p.num_dofs();
    m_ = p.size();
    nc_ = p.num_contacts();
    reduction_.compute(p, /*form_W=*/false);
    this->q_norm_ = reduction_.free_velocity_norm();
    // Hs = H D^-1, w0 = D^-1 w (form_common.hpp: a frictionless contact's
    // tangential columns and entries are 0)
    Hs_ = SparseMatrix(p.H);
    w0_ = p.w;
    for (Index a = 0; a < nc_; ++a) {
      if (frictionless(p.mu[a])) {
        for (int k = 1; k < D; ++k) Hs_.col(a * D + k) *= 0.0;
        w0_.template segment<D - 1>(a * D + 1).setZero();
      } else {
        Hs_.col(a * D) /= p.mu[a];
        w0_[a * D] /= p.mu[a];
      }
    }
    Hs_.makeCompressed();
    this->symmetric_data_ = relative_asymmetry(p.M) <= kSymmetryRoundoff;
    // A0 = [M -Hs; -Hs^T 0], G = [0; I].
    std::vector<Eigen::Triplet<double, int>> t;
    t.reserve(std::size_t(p.M.nonZeros() + 2 * Hs_.nonZeros()));
    for (Index j = 0; j < n_; ++j)
      for (SparseMap::InnerIterator it(p.M, j); it; ++it) t.emplace_back(int(it.row()), int(j), it.value());
    for (Index j = 0; j < m_; ++j)
      for (SparseMatrix::InnerIterator it(Hs_, j); it; ++it) {
        t.emplace_back(int(it.row()), int(n_ + j), -it.value());
        t.emplace_back(int(n_ + j), int(it.row()), -it.value());
      }
    SparseMatrix A0(n_ + m_, n_ + m_), G(n_ + m_, m_);
    A0.setFromTriplets(t.begin(), t.end());
    t.clear();
    for (Index j = 0; j < m_; ++j) t.emplace_back(int(n_ + j), int(j), 1.0);
    G.setFromTriplets(t.begin(), t.end());
    this->kkt_.compute(A0, G, this->symmetric_data_);
    // Units of the regularisation: mean diagonal of M, and theta^2, the
    // typical diagonal of W = Hs^T M^-1 Hs (the contact block's scale).
    double tr = 0;
    for (Index j = 0; j < n_; ++j)
      for (SparseMap::InnerIterator it(p.M, j); it; ++it)
        if (it.row() == j) tr += std::abs(it.value());
    const double hn = Hs_.squaredNorm();
    const double mass = tr > 0 ? tr / double(n_) : 1.0;
    this->theta_ = (tr > 0 && hn > 0) ? std::sqrt(hn / tr) : 1.0;
    this->kkt_.regularization_weights().head(n_).setConstant(mass);
    this->kkt_.regularization_weights().tail(m_).setConstant(-this->theta_ * this->theta_);
    rhs_.resize(n_ + m_);
    sol_.resize(n_ + m_);
    r_.resize(m_);
    u_.resize(m_);
    Mv_.resize(n_);
    Hr_.resize(n_);
  }

  Index primal_size() const { return n_; }
  double diagonal_scale() const { return 1.0; }  // weights carry the units
  /// ||H^T M^-1 f + w|| (0 allowed), from the factorisation of M in compute().
  double free_velocity_norm() const { return this->q_norm_; }
  /// M factorised once: v = M^-1 (H r + f).
  const GlobalReduction<EigenBackend>& reduction() const { return reduction_; }

  /// r_d = M v - Hs y - f,  r_p = Hs^T v + w0 + E s - x.
  void residuals(const Iterate& it, Vector& r_d, Vector& r_p) const {
    r_d.noalias() = p_->M * it.v;
    r_d.noalias() -= Hs_ * it.y;
    r_d -= p_->f;
    r_p.noalias() = Hs_.transpose() * it.v;
    r_p += w0_ - it.x;
    add_friction_shift<D>(r_p, it.s, p_->mu);
  }

  /// The Newton direction for the complementarity right-hand side xi
  /// (T^-1 dx + T dy = xi) and residuals r_d, r~p (header comment).
  void direction(const ContactState<D>& cs, const Vector& xi, const Vector& r_d,
                 const Vector& rp_tilde, Iterate& d, int refinement) {
    rhs_.head(n_) = -r_d;
    for (Index a = 0; a < nc_; ++a) {
      Vec<D> txi = cs.scaling[std::size_t(a)].T * xi.template segment<D>(a * D);
      txi[0] -= cs.normal[std::size_t(a)].dot(txi);
      rhs_.template segment<D>(n_ + a * D) = rp_tilde.template segment<D>(a * D) - txi;
    }
    this->kkt_.solve(rhs_, sol_, refinement);
    d.v = sol_.head(n_);
    d.y = sol_.tail(m_);
    d.x.noalias() = Hs_.transpose() * d.v;
    d.x += rp_tilde;
    apply_coupling<D>(cs, d.x);
  }

  /// Same with T = theta I, P = I (initial point).
  void direction_uniform(double theta, const Vector& xi, const Vector& r_d, const Vector& r_p,
                         Iterate& d) {
    rhs_.head(n_) = -r_d;
    rhs_.tail(m_) = r_p - theta * xi;
    this->kkt_.solve(rhs_, sol_, 2);
    d.v = sol_.head(n_);
    d.y = sol_.tail(m_);
    d.x.noalias() = Hs_.transpose() * d.v;
    d.x += r_p;
  }

  /// u = H^T v + w (the data's H, not the scaled one).
  void velocity(const Iterate& it, Vector& u) const {
    u.noalias() = p_->H.transpose() * it.v;
    u += p_->w;
  }

  /// v = M^-1 (H r + f) of a given r (a warm start) and the error of (r, v):
  /// the FCLIB error, or with `frozen` the one of the problem with s frozen.
  double error_of(const Vector& r, Vector& v, const Vector& s, bool frozen) const {
    v = reduction_.velocity(r);
    const Vector u = p_->H.transpose() * v + p_->w;
    const Vector Mv = p_->M * v, Hr = p_->H * r;
    const double denom = std::max({p_->f.norm(), Mv.norm(), Hr.norm()});
    const double equil = (Mv - Hr - p_->f).norm() / (denom > 0 ? denom : 1.0);
    return std::max(std::sqrt(natural_map_squared<D>(r, u, p_->mu, s, frozen)) / error_scale(),
                    equil);
  }

  /// FCLIB error of (r, v) (core/error.hpp; equal to global_error_report
  /// without bilateral constraints), or with `frozen` the error of the
  /// problem with s frozen (u~ = u + A s).
  double error(const Iterate& it, bool frozen) {
    reaction(it, r_);
    velocity(it, u_);
    const double comp = natural_map_squared<D>(r_, u_, p_->mu, it.s, frozen);
    Mv_.noalias() = p_->M * it.v;
    Hr_.noalias() = p_->H * r_;
    const double denom = std::max({p_->f.norm(), Mv_.norm(), Hr_.norm()});
    const double equil = (Mv_ - Hr_ - p_->f).norm() / (denom > 0 ? denom : 1.0);
    return std::max(std::sqrt(comp) / error_scale(), equil);
  }

 private:
  Index n_ = 0;
  // M once, for ||q|| and v = M^-1 (H r + f): Eigen's simplicial LDL^T (or
  // LU) has less set-up cost than CHOLMOD's supernodal one on the diagonal
  // or block-diagonal M of multibody scenes, and runs once.
  GlobalReduction<EigenBackend> reduction_;
  SparseMatrix Hs_;
  Vector w0_;
  Vector rhs_, sol_, r_, u_, Mv_, Hr_;
};

}  // namespace ipm
}  // namespace fcsolve
