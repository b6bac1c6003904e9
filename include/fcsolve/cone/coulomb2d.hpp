// The 2D Coulomb friction cone (FCLIB spacedim = 2), normal first:
//   K_mu = { (r_N, r_T) : |r_T| <= mu r_N },  K_mu* = { mu |u_T| <= u_N }.
#pragma once

#include <fcsolve/core/types.hpp>

#include <cmath>

namespace fcsolve {

template <class Scalar_>
struct Coulomb2DTpl {
  using Scalar = Scalar_;
  static constexpr int dim = 2;
  using Vec = SmallVector<2, Scalar>;

  static Scalar tangential_norm(const Vec& z) { return std::abs(z[1]); }

  /// Projection onto K_mu: the 3D closed form with a scalar tangent.
  static Vec project(const Vec& z, Scalar mu) {
    const Scalar zn = z[0], nt = std::abs(z[1]);
    if (nt <= mu * zn && zn >= 0) return z;
    if (mu * nt <= -zn) return Vec::Zero();
    const Scalar a = (zn + mu * nt) / (Scalar(1) + mu * mu);
    return Vec(a, std::copysign(mu * a, z[1]));
  }
  static Vec project_dual(const Vec& z, Scalar mu) { return z + project(Vec(-z), mu); }

  static Vec de_saxce_shift(const Vec& u, Scalar mu) {
    return Vec(mu * std::abs(u[1]), Scalar(0));
  }
  static Vec modified_velocity(const Vec& u, Scalar mu) { return u + de_saxce_shift(u, mu); }

  static bool contains(const Vec& r, Scalar mu, Scalar tol = 0) {
    return r[0] >= -tol && std::abs(r[1]) <= mu * r[0] + tol;
  }
  static bool contains_dual(const Vec& u, Scalar mu, Scalar tol = 0) {
    return u[0] >= -tol && mu * std::abs(u[1]) <= u[0] + tol;
  }
};

using Coulomb2D = Coulomb2DTpl<double>;

}  // namespace fcsolve
