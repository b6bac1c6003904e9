// G(r, u) = [ G^a(r^a, u^a) ]_a of a formulation, contact by contact, with
// the Jacobian blocks A^a, B^a (dG = A du + B dr) and the per-contact rho.
// Shared by the reduced and the global Newton solvers.
#pragma once

#include <fcsolve/core/types.hpp>
#include <fcsolve/newton/rho_strategy.hpp>

#include <cmath>
#include <optional>
#include <vector>

namespace fcsolve {

template <class Function, int D>
class ContactResidual {
 public:
  using Vec = SmallVector<D>;
  using Mat = SmallMatrix<D>;
  using Blocks = std::vector<Mat, Eigen::aligned_allocator<Mat>>;

  /// `diagonal(a)` returns (an approximation of) W^aa for the rho strategy.
  template <class DiagonalBlock>
  void compute(const VectorMap& mu, RhoStrategy strategy, double factor, DiagonalBlock&& diagonal) {
    mu_.emplace(mu);
    const Index nc = mu.size();
    base_rho_.resize(static_cast<std::size_t>(nc));
    for (Index a = 0; a < nc; ++a) base_rho_[a] = contact_rho<D>(strategy, factor, diagonal(a));
    rho_ = base_rho_;
    A_.resize(static_cast<std::size_t>(nc));
    B_.resize(static_cast<std::size_t>(nc));
    G_.resize(nc * D);
  }

  /// rho = kappa * (rho of the strategy)
  void set_rho_factor(double kappa) {
    for (std::size_t a = 0; a < rho_.size(); ++a) rho_[a] = kappa * base_rho_[a];
  }

  /// psi = 1/2 ||G(r, u)||^2; G stored, and A, B if `jacobian`.
  double evaluate(const Eigen::Ref<const Vector>& r, const Eigen::Ref<const Vector>& u, bool jacobian) {
    const VectorMap& mu = *mu_;
    double sum = 0;
    for (Index a = 0; a < mu.size(); ++a) {
      const Vec ra = r.template segment<D>(a * D), ua = u.template segment<D>(a * D);
      Vec Ga;
      if (jacobian) Function::value_and_jacobian(ra, ua, mu[a], rho_[a], Ga, A_[a], B_[a]);
      else Ga = Function::value(ra, ua, mu[a], rho_[a]);
      G_.template segment<D>(a * D) = Ga;
      sum += Ga.squaredNorm();
    }
    return 0.5 * sum;
  }

  /// psi at (r + t dr, u + t du); nothing stored.
  double trial(const Eigen::Ref<const Vector>& r, const Eigen::Ref<const Vector>& dr,
               const Eigen::Ref<const Vector>& u, const Eigen::Ref<const Vector>& du, double t) const {
    const VectorMap& mu = *mu_;
    double sum = 0;
    for (Index a = 0; a < mu.size(); ++a) {
      const Vec ra = r.template segment<D>(a * D) + t * dr.template segment<D>(a * D);
      const Vec ua = u.template segment<D>(a * D) + t * du.template segment<D>(a * D);
      sum += Function::value(ra, ua, mu[a], rho_[a]).squaredNorm();
    }
    return 0.5 * sum;
  }

  /// ||G(0, u0)|| (1 if that is 0): the scale of ||G|| of the
  /// Levenberg-Marquardt shift, with u0 the free velocity (r = 0).
  double reference_norm(const Eigen::Ref<const Vector>& u0) {
    const double g0 = std::sqrt(2 * evaluate(Vector::Zero(u0.size()), u0, false));
    return g0 > 0 && std::isfinite(g0) ? g0 : 1.0;
  }

  const Vector& G() const { return G_; }
  const Blocks& A() const { return A_; }
  const Blocks& B() const { return B_; }

 private:
  std::optional<VectorMap> mu_;
  std::vector<Vec, Eigen::aligned_allocator<Vec>> rho_, base_rho_;
  Blocks A_, B_;
  Vector G_;
};

}  // namespace fcsolve
