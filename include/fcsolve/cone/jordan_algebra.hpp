// The Jordan algebra of the second-order (Lorentz) cone
//   L^N = { x = (x0, xb) in R x R^{N-1} : ||xb|| <= x0 },
// used by the SOCCP Fischer-Burmeister function and the interior-point
// methods (Faraut & Koranyi 1994; Fukushima, Luo & Tseng, SIAM J. Optim. 12,
// 2002, sec. 2; Alizadeh & Goldfarb, Math. Program. 95, 2003, sec. 4):
//   x o y = (x^T y, x0 yb + y0 xb),   e = (1, 0),
//   spectral decomposition x = l1 c1 + l2 c2,
//     l_i = x0 + (-1)^i ||xb||,  c_i = (1, (-1)^i w) / 2,  w = xb / ||xb||
//   (any unit w when xb = 0), so x in L iff l1 >= 0, x in int L iff l1 > 0.
//
// The Coulomb cone K_mu = { ||r_T|| <= mu r_N } is mapped onto L^N by
// r -> D_mu r with D_mu = diag(mu, 1, ..., 1); its dual K_mu* by
// u -> D_mu^-1 u (up to the positive factor mu), and r^T u = (D r)^T (D^-1 u).
#pragma once

#include <fcsolve/core/types.hpp>

#include <cmath>

namespace fcsolve {
namespace jordan {

template <int N>
using Vec = SmallVector<N>;
template <int N>
using Mat = SmallMatrix<N>;

template <int N>
struct Spectral {
  double lambda1 = 0, lambda2 = 0;  ///< lambda1 <= lambda2
  Vec<N> c1, c2;                    ///< Jordan frame: c1 + c2 = e, c1 o c2 = 0
};

/// Spectral decomposition x = lambda1 c1 + lambda2 c2.
template <int N>
Spectral<N> spectral(const Vec<N>& x) {
  const auto xb = x.template tail<N - 1>();
  const double nb = xb.norm();
  Vec<N - 1> w;
  if (nb > 0) {
    w = xb / nb;
  } else {
    w.setZero();
    w[0] = 1;  // any unit vector: the decomposition is not unique at xb = 0
  }
  Spectral<N> s;
  s.lambda1 = x[0] - nb;
  s.lambda2 = x[0] + nb;
  s.c1[0] = 0.5;
  s.c1.template tail<N - 1>() = -0.5 * w;
  s.c2[0] = 0.5;
  s.c2.template tail<N - 1>() = 0.5 * w;
  return s;
}

/// Jordan product x o y.
template <int N>
Vec<N> product(const Vec<N>& x, const Vec<N>& y) {
  Vec<N> z;
  z[0] = x.dot(y);
  z.template tail<N - 1>() = x[0] * y.template tail<N - 1>() + y[0] * x.template tail<N - 1>();
  return z;
}

/// Arrow matrix L(x): x o y = L(x) y.
template <int N>
Mat<N> arrow(const Vec<N>& x) {
  Mat<N> L = x[0] * Mat<N>::Identity();
  L.template block<1, N - 1>(0, 1) = x.template tail<N - 1>().transpose();
  L.template block<N - 1, 1>(1, 0) = x.template tail<N - 1>();
  return L;
}

/// det(x) = x0^2 - ||xb||^2 = lambda1 lambda2.
template <int N>
double det(const Vec<N>& x) {
  return x[0] * x[0] - x.template tail<N - 1>().squaredNorm();
}

/// x^-1 = (x0, -xb) / det(x) (x invertible: det(x) != 0).
template <int N>
Vec<N> inverse(const Vec<N>& x) {
  Vec<N> y = x;
  y.template tail<N - 1>() *= -1;
  return y / det(x);
}

/// x^(1/2) for x in L (negative eigenvalues clipped to 0).
template <int N>
Vec<N> sqrt(const Vec<N>& x) {
  const Spectral<N> s = spectral(x);
  return std::sqrt(std::max(s.lambda1, 0.0)) * s.c1 + std::sqrt(std::max(s.lambda2, 0.0)) * s.c2;
}

/// Quadratic representation P(x) = 2 L(x)^2 - L(x o x)
///   = [ ||x||^2, 2 x0 xb^T ; 2 x0 xb, det(x) I + 2 xb xb^T ].
template <int N>
Mat<N> quadratic_representation(const Vec<N>& x) {
  const auto xb = x.template tail<N - 1>();
  Mat<N> P;
  P(0, 0) = x.squaredNorm();
  P.template block<1, N - 1>(0, 1) = 2 * x[0] * xb.transpose();
  P.template block<N - 1, 1>(1, 0) = 2 * x[0] * xb;
  P.template block<N - 1, N - 1>(1, 1) =
      det(x) * Mat<N - 1>::Identity() + 2 * xb * xb.transpose();
  return P;
}

/// Projection onto L^N: clip the spectral values at 0.
template <int N>
Vec<N> project(const Vec<N>& x) {
  const Spectral<N> s = spectral(x);
  return std::max(s.lambda1, 0.0) * s.c1 + std::max(s.lambda2, 0.0) * s.c2;
}

/// D_mu r: maps K_mu onto L^N (mu > 0).
template <int N>
Vec<N> to_lorentz(const Vec<N>& r, double mu) {
  Vec<N> y = r;
  y[0] *= mu;
  return y;
}
/// D_mu^-1 u: maps K_mu* onto L^N up to the factor mu (mu > 0).
template <int N>
Vec<N> dual_to_lorentz(const Vec<N>& u, double mu) {
  Vec<N> z = u;
  z[0] /= mu;
  return z;
}

}  // namespace jordan
}  // namespace fcsolve
