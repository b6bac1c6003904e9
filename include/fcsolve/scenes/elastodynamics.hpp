// Linear elastodynamics (small strain) stepped by the Moreau-Jean scheme
// (Acary & Brogliato 2008, sec. 10.1 on linear systems; Jean 1999). With the
// displacement x, the velocity v, the stiffness K and the mass M:
//   M (v+ - v) = -h K x_theta + h f_ext(t + theta h) + H r,
//   x_theta = x + h theta (theta v+ + (1 - theta) v),
//   x+ = x + h (theta v+ + (1 - theta) v),
// that is FC/I (M_hat v+ = f + H r, u = H^T v+ + w) with
//   M_hat = M + h^2 theta^2 K                      (full rank, stiffness inside)
//   f = M v - h K (x + h theta (1 - theta) v) + h f_ext.
// M_hat is constant: it is factorised once, for the free velocity
// M_hat^-1 f that decides which contacts are active.
#pragma once

#include <fcsolve/core/types.hpp>
#include <fcsolve/linalg/default_backend.hpp>

#include <stdexcept>

namespace fcsolve::scenes {

class LinearElastodynamics {
 public:
  LinearElastodynamics(SparseMatrix K, SparseMatrix M, double h, double theta)
      : K_(std::move(K)), M_(std::move(M)), h_(h), theta_(theta) {
    M_hat_ = M_ + (h * h * theta * theta) * K_;
    K_.makeCompressed();
    M_.makeCompressed();
    M_hat_.makeCompressed();
    x_ = Vector::Zero(M_.rows());
    v_ = Vector::Zero(M_.rows());
    factor_.compute(M_hat_);
    if (factor_.info() != Eigen::Success) throw std::runtime_error("M_hat is not positive definite");
  }

  Index dofs() const { return M_.rows(); }
  const SparseMatrix& M() const { return M_; }
  const SparseMatrix& M_hat() const { return M_hat_; }
  const Vector& displacement() const { return x_; }
  const Vector& velocity() const { return v_; }

  /// f = M v - h K (x + h theta (1 - theta) v) + h f_ext.
  Vector step_force(const Vector& f_ext) const {
    return M_ * v_ - h_ * (K_ * (x_ + (h_ * theta_ * (1 - theta_)) * v_)) + h_ * f_ext;
  }
  Vector free_velocity(const Vector& f) const { return factor_.solve(f); }

  void advance(const Vector& v_next) {
    x_ += h_ * (theta_ * v_next + (1 - theta_) * v_);
    v_ = v_next;
  }

 private:
  SparseMatrix K_, M_, M_hat_;
  double h_, theta_;
  Vector x_, v_;
  DefaultBackend::SymmetricSolver factor_;
};

}  // namespace fcsolve::scenes
