// The 3D Coulomb friction cone, normal component first (FCLIB convention):
//   K_mu  = { r in R^3 : ||r_T|| <= mu r_N },
//   K_mu* = { u in R^3 : mu ||u_T|| <= u_N }   (dual cone, aperture 1/mu).
#pragma once

#include <fcsolve/core/types.hpp>

#include <cmath>

namespace fcsolve {

template <class Scalar_>
struct Coulomb3DTpl {
  using Scalar = Scalar_;
  static constexpr int dim = 3;
  using Vec = SmallVector<3, Scalar>;

  // sqrt, not std::hypot: hypot's overflow guard costs ~10x in the NSGS
  // sweep, and entries near 1e154 are not contact data.
  static Scalar tangential_norm(const Vec& z) { return std::sqrt(z[1] * z[1] + z[2] * z[2]); }

  /// Euclidean projection onto K_mu. Closed form for a second-order cone with
  /// aperture mu (e.g. Acary & Brogliato 2008, sec. 12.4; Fukushima, Luo &
  /// Tseng 2002 for the Lorentz cone): inside -> z, in the polar cone -> 0,
  /// otherwise onto the boundary ray through the tangential direction of z.
  static Vec project(const Vec& z, Scalar mu) {
    const Scalar zn = z[0], nt = tangential_norm(z);
    if (nt <= mu * zn && zn >= 0) return z;  // z in K (zn >= 0 matters when mu = 0)
    if (mu * nt <= -zn) return Vec::Zero();  // z in the polar cone K°
    const Scalar a = (zn + mu * nt) / (Scalar(1) + mu * mu);
    const Scalar s = mu * a / nt;  // nt > 0 here (see the two tests above)
    return Vec(a, s * z[1], s * z[2]);
  }

  /// Projection onto the dual cone, by Moreau: P_{K*}(z) = z + P_K(-z).
  static Vec project_dual(const Vec& z, Scalar mu) { return z + project(Vec(-z), mu); }

  /// De Saxce's shift g(u) = (mu ||u_T||, 0, 0) (De Saxce 1992), so that the
  /// modified velocity u + g(u) lies in K* exactly when Coulomb's law holds.
  static Vec de_saxce_shift(const Vec& u, Scalar mu) {
    return Vec(mu * tangential_norm(u), Scalar(0), Scalar(0));
  }
  static Vec modified_velocity(const Vec& u, Scalar mu) { return u + de_saxce_shift(u, mu); }

  /// Membership with an absolute slack `tol` (tol = 0: exact test).
  /// Squares are compared (b >= 0 checked first): the square root was on
  /// the critical path of every stick test of the exact local solver.
  static bool contains(const Vec& r, Scalar mu, Scalar tol = 0) {
    const Scalar bound = mu * r[0] + tol;
    return r[0] >= -tol && bound >= 0 && r[1] * r[1] + r[2] * r[2] <= bound * bound;
  }
  static bool contains_dual(const Vec& u, Scalar mu, Scalar tol = 0) {
    return u[0] >= -tol && mu * tangential_norm(u) <= u[0] + tol;
  }
};

using Coulomb3D = Coulomb3DTpl<double>;

}  // namespace fcsolve
