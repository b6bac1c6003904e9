// The Jordan algebra of the second-order (Lorentz) cone
//   L^D = { x = (x0, xb) in R x R^{D-1} : ||xb|| <= x0 },
// used by the SOCCP Fischer-Burmeister function and the interior-point
// methods (Faraut & Koranyi 1994; Fukushima, Luo & Tseng, SIAM J. Optim. 12,
// 2002, sec. 2; Alizadeh & Goldfarb, Math. Program. 95, 2003, sec. 4):
//   x o y = (x^T y, x0 yb + y0 xb),   e = (1, 0),
//   spectral decomposition x = l1 c1 + l2 c2,
//     l_i = x0 + (-1)^i ||xb||,  c_i = (1, (-1)^i w) / 2,  w = xb / ||xb||
//   (any unit w when xb = 0), so x in L iff l1 >= 0, x in int L iff l1 > 0.
//
// The Coulomb cone K_mu = { ||r_T|| <= mu r_N } is mapped onto L^D by
// r -> D_mu r with D_mu = diag(mu, 1, ..., 1); its dual K_mu* by
// u -> D_mu^-1 u (up to the positive factor mu), and r^T u = (D r)^T (D^-1 u).
#pragma once

#include <fcsolve/core/types.hpp>

#include <cmath>

namespace fcsolve {
namespace jordan {

template <int D>
using Vec = SmallVector<D>;
template <int D>
using Mat = SmallMatrix<D>;

template <int D>
struct Spectral {
  double lambda1 = 0, lambda2 = 0;  ///< lambda1 <= lambda2
  Vec<D> c1, c2;                    ///< Jordan frame: c1 + c2 = e, c1 o c2 = 0
};

/// Spectral decomposition x = lambda1 c1 + lambda2 c2.
template <int D>
Spectral<D> spectral(const Vec<D>& x) {
  const auto xb = x.template tail<D - 1>();
  const double nb = xb.norm();
  Vec<D - 1> w;
  if (nb > 0) {
    w = xb / nb;
  } else {
    w.setZero();
    w[0] = 1;  // any unit vector: the decomposition is not unique at xb = 0
  }
  Spectral<D> s;
  s.lambda1 = x[0] - nb;
  s.lambda2 = x[0] + nb;
  s.c1[0] = 0.5;
  s.c1.template tail<D - 1>() = -0.5 * w;
  s.c2[0] = 0.5;
  s.c2.template tail<D - 1>() = 0.5 * w;
  return s;
}

/// Jordan product x o y.
template <int D>
Vec<D> product(const Vec<D>& x, const Vec<D>& y) {
  Vec<D> z;
  z[0] = x.dot(y);
  z.template tail<D - 1>() = x[0] * y.template tail<D - 1>() + y[0] * x.template tail<D - 1>();
  return z;
}

/// Arrow matrix L(x): x o y = L(x) y.
template <int D>
Mat<D> arrow(const Vec<D>& x) {
  Mat<D> L = x[0] * Mat<D>::Identity();
  L.template block<1, D - 1>(0, 1) = x.template tail<D - 1>().transpose();
  L.template block<D - 1, 1>(1, 0) = x.template tail<D - 1>();
  return L;
}

/// det(x) = x0^2 - ||xb||^2 = lambda1 lambda2.
template <int D>
double det(const Vec<D>& x) {
  return x[0] * x[0] - x.template tail<D - 1>().squaredNorm();
}

/// x^-1 = (x0, -xb) / det(x) (x invertible: det(x) != 0).
template <int D>
Vec<D> inverse(const Vec<D>& x) {
  Vec<D> y = x;
  y.template tail<D - 1>() *= -1;
  return y / det(x);
}

/// x^(1/2) for x in L (negative eigenvalues clipped to 0).
template <int D>
Vec<D> sqrt(const Vec<D>& x) {
  const Spectral<D> s = spectral(x);
  return std::sqrt(std::max(s.lambda1, 0.0)) * s.c1 + std::sqrt(std::max(s.lambda2, 0.0)) * s.c2;
}

/// Quadratic representation P(x) = 2 L(x)^2 - L(x o x)
///   = [ ||x||^2, 2 x0 xb^T ; 2 x0 xb, det(x) I + 2 xb xb^T ].
template <int D>
Mat<D> quadratic_representation(const Vec<D>& x) {
  const auto xb = x.template tail<D - 1>();
  Mat<D> P;
  P(0, 0) = x.squaredNorm();
  P.template block<1, D - 1>(0, 1) = 2 * x[0] * xb.transpose();
  P.template block<D - 1, 1>(1, 0) = 2 * x[0] * xb;
  P.template block<D - 1, D - 1>(1, 1) =
      det(x) * Mat<D - 1>::Identity() + 2 * xb * xb.transpose();
  return P;
}

/// Projection onto L^D: clip the spectral values at 0.
template <int D>
Vec<D> project(const Vec<D>& x) {
  const Spectral<D> s = spectral(x);
  return std::max(s.lambda1, 0.0) * s.c1 + std::max(s.lambda2, 0.0) * s.c2;
}

/// D_mu r: maps K_mu onto L^D (mu > 0).
template <int D>
Vec<D> to_lorentz(const Vec<D>& r, double mu) {
  Vec<D> y = r;
  y[0] *= mu;
  return y;
}
/// D_mu^-1 u: maps K_mu* onto L^D up to the factor mu (mu > 0).
template <int D>
Vec<D> dual_to_lorentz(const Vec<D>& u, double mu) {
  Vec<D> z = u;
  z[0] /= mu;
  return z;
}

}  // namespace jordan
}  // namespace fcsolve
