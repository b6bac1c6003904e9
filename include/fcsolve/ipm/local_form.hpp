// The local (reduced) form of the interior-point Newton step, on
// FC/II(W, q, mu): the unknowns are x, y (and s), the linear system is
//   K = Ws + P^-1 T^2,   Ws = D^-1 W D^-1,
// m x m with W's pattern plus the diagonal blocks: symmetric positive
// definite when s is frozen and W symmetric positive semidefinite (Cholesky),
// unsymmetric otherwise (LU). From (form_common.hpp)
//   dx = Ws dy + E ds + r_p,  ds = n^T dx - r_s,  T^-1 dx + T dy = xi
// follow dx = P (Ws dy + r~p) and  K dy = P^-1 T xi - r~p,  P^-1 = I - e n^T.
// A rank-deficient W makes K singular in the limit (sticking contacts have
// T -> 0): the static regularisation of KktSystem handles that.
#pragma once

#include <fcsolve/ipm/form_base.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/problem/local_problem.hpp>
#include <fcsolve/problem/symmetry.hpp>

#include <cmath>

namespace fcsolve {
namespace ipm {

template <class ConeType, class Factorization>
class LocalForm : public FormBase<ConeType, Factorization, LocalProblemView, +1> {
  using Base = FormBase<ConeType, Factorization, LocalProblemView, +1>;
  using Base::m_, Base::nc_, Base::p_;

 public:
  using Base::D, Base::error_scale, Base::reaction;
  static constexpr bool is_global = false;

  void compute(const LocalProblemView& p) {
    p_.emplace(p);
    m_ = p.size();
    nc_ = p.num_contacts();
    const Vector dinv = lorentz_inverse_scaling<D>(p.mu);
    Ws_ = dinv.asDiagonal() * SparseMatrix(p.W) * dinv.asDiagonal();
    Ws_.makeCompressed();
    q0_ = dinv.cwiseProduct(Vector(p.q));
    this->symmetric_data_ = relative_asymmetry(p.W) <= kSymmetryRoundoff;
    SparseMatrix I(m_, m_);
    I.setIdentity();
    this->kkt_.compute(Ws_, I, this->symmetric_data_);
    this->q_norm_ = p.q.norm();
    const double tr = Ws_.diagonal().cwiseAbs().sum();
    this->theta_ = tr > 0 ? std::sqrt(tr / double(m_)) : 1.0;
    diag_scale_ = tr > 0 ? tr / double(m_) : 1.0;
    r_.resize(m_);
    u_.resize(m_);
    rhs_.resize(m_);
  }

  Index primal_size() const { return 0; }
  /// Typical diagonal of K: the unit of the static regularisation.
  double diagonal_scale() const { return diag_scale_; }

  /// r_p = Ws y + q0 + E s - x (no r_d in this form).
  void residuals(const Iterate& it, Vector& r_d, Vector& r_p) const {
    r_d.resize(0);
    r_p.noalias() = Ws_ * it.y;
    r_p += q0_ - it.x;
    add_friction_shift<D>(r_p, it.s, p_->mu);
  }

  void direction(const ContactState<D>& cs, const Vector& xi, const Vector& /*r_d*/,
                 const Vector& rp_tilde, Iterate& d, int refinement) {
    for (Index a = 0; a < nc_; ++a) {
      Vec<D> txi = cs.scaling[std::size_t(a)].T * xi.template segment<D>(a * D);
      txi[0] -= cs.normal[std::size_t(a)].dot(txi);
      rhs_.template segment<D>(a * D) = txi - rp_tilde.template segment<D>(a * D);
    }
    this->kkt_.solve(rhs_, d.y, refinement);
    d.x.noalias() = Ws_ * d.y;
    d.x += rp_tilde;
    apply_coupling<D>(cs, d.x);
  }

  void direction_uniform(double theta, const Vector& xi, const Vector& /*r_d*/, const Vector& r_p,
                         Iterate& d) {
    rhs_ = theta * xi - r_p;
    this->kkt_.solve(rhs_, d.y, 2);
    d.x.noalias() = Ws_ * d.y;
    d.x += r_p;
  }

  /// u = W r + q for the reaction of `it`.
  void velocity(const Iterate& it, Vector& u) const {
    Vector r(m_);
    reaction(it, r);
    u.noalias() = p_->W * r;
    u += p_->q;
  }

  /// u = W r + q of a given r (a warm start) and the error of (r, u): the
  /// FCLIB error, or with `frozen` the one of the problem with s frozen.
  double error_of(const Vector& r, Vector& u, const Vector& s, bool frozen) const {
    u.noalias() = p_->W * r;
    u += p_->q;
    return std::sqrt(natural_map_squared<D>(r, u, p_->mu, s, frozen)) / error_scale();
  }

  /// FCLIB error ||F_nat|| / ||q|| (or with s frozen, see GlobalForm::error).
  double error(const Iterate& it, bool frozen) {
    reaction(it, r_);
    u_.noalias() = p_->W * r_;
    u_ += p_->q;
    const double comp = natural_map_squared<D>(r_, u_, p_->mu, it.s, frozen);
    return std::sqrt(comp) / error_scale();
  }

 private:
  SparseMatrix Ws_;
  Vector q0_;
  double diag_scale_ = 1;
  Vector r_, u_, rhs_;
};

}  // namespace ipm
}  // namespace fcsolve
