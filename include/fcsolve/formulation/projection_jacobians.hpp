// Projections used by the one-contact nonsmooth functions of the Newton
// family, each with one element of its generalised (Clarke) Jacobian:
//   - the disk (or interval, in 2D) D(R) = { ||x|| <= R }, as a function of
//     the point x and of the radius R (Alart & Curnier 1991, sec. 3);
//   - the Coulomb cone K_mu (the closed form of Cone::project, same branches);
//   - De Saxce's shift g(u) = (mu ||u_T||, 0).
// Where a function is not differentiable (on a region boundary) the element
// returned is the derivative of one of the adjacent smooth pieces, which is
// an element of the B-subdifferential (Qi & Sun 1993).
#pragma once

#include <fcsolve/core/types.hpp>

#include <cmath>

namespace fcsolve {

/// p = P_{D(R)}(x) with dp = dp_dx dx + dp_dR dR, tangent dimension T (1 or 2).
/// R <= 0: the disk is {0}, p = 0 and both derivatives are 0 (a contact that
/// takes off; callers make R depend on the normal part only when R > 0).
/// ||x|| <= R: p = x (stick).  Otherwise p = R x/||x|| (slide):
///   dp = (R/||x||)(I - n n^T) dx + n dR,  n = x/||x||.
template <int T>
void project_on_disk(const SmallVector<T>& x, double R, SmallVector<T>& p, SmallMatrix<T>& dp_dx,
                     SmallVector<T>& dp_dR) {
  const double nx = x.norm();
  if (R <= 0) {
    p.setZero();
    dp_dx.setZero();
    dp_dR.setZero();
  } else if (nx <= R) {
    p = x;
    dp_dx.setIdentity();
    dp_dR.setZero();
  } else {
    const SmallVector<T> n = x / nx;
    p = R * n;
    dp_dx = (R / nx) * (SmallMatrix<T>::Identity() - n * n.transpose());
    dp_dR = n;
  }
}

/// The Jacobian J of P_{K_mu}(z) for the Coulomb cone of dimension D >= 2
/// (normal first), with the branches of Coulomb3D/2D::project:
///   z in K -> I;  z in the polar cone -> 0;  otherwise, with a = (z_N +
///   mu ||z_T||)/(1 + mu^2), n = z_T/||z_T|| and P = (a, mu a n):
///   J = 1/(1+mu^2) [1, mu n^T; mu n, mu^2 n n^T] + [0, 0; 0, (mu a/||z_T||)(I - n n^T)]
/// (derived here by differentiating a and n; the Lorentz-cone case mu = 1 is
/// in Pang, Sun & Sun, Math. Oper. Res. 28, 2003).
template <int D>
SmallMatrix<D> coulomb_projection_jacobian(const SmallVector<D>& z, double mu) {
  static_assert(D >= 2, "the Coulomb cone has a tangential part");
  constexpr int T = D - 1;
  const double zn = z[0];
  const SmallVector<T> zt = z.template tail<T>();
  const double nt = zt.norm();
  if (nt <= mu * zn && zn >= 0) return SmallMatrix<D>::Identity();
  if (mu * nt <= -zn) return SmallMatrix<D>::Zero();
  const SmallVector<T> n = zt / nt;  // nt > 0 here, see Coulomb3D::project
  const double a = (zn + mu * nt) / (1 + mu * mu);
  SmallMatrix<D> J;
  J(0, 0) = 1;
  J.template block<1, T>(0, 1) = mu * n.transpose();
  J.template block<T, 1>(1, 0) = mu * n;
  J.template block<T, T>(1, 1) = mu * mu * n * n.transpose();
  J /= 1 + mu * mu;
  J.template block<T, T>(1, 1) +=
      (mu * a / nt) * (SmallMatrix<T>::Identity() - n * n.transpose());
  return J;
}

/// I + Dg(u): the Jacobian of the modified velocity u + g(u), with
/// g(u) = (mu ||u_T||, 0) (De Saxce 1992). At u_T = 0 the element taken is
/// the zero subgradient of ||.||, i.e. I.
template <int D>
SmallMatrix<D> modified_velocity_jacobian(const SmallVector<D>& u, double mu) {
  SmallMatrix<D> J = SmallMatrix<D>::Identity();
  if constexpr (D >= 2) {
    const auto ut = u.template tail<D - 1>();
    const double nt = ut.norm();
    if (nt > 0 && mu > 0) J.template block<1, D - 1>(0, 1) = (mu / nt) * ut.transpose();
  }
  return J;
}

}  // namespace fcsolve
