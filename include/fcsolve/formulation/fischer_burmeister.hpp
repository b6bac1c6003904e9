// The SOCCP Fischer-Burmeister function of one contact [NSN-FB] (Fukushima,
// Luo & Tseng, SIAM J. Optim. 12, 2002, sec. 2 and 5; Acary, Bremond & Huber
// 2018, "extension of the Fischer-Burmeister function to SOCCP"):
//   phi(x, y) = x + y - (x o x + y o y)^{1/2}     (Jordan algebra of L^D)
//   G(r, u)   = phi(x, y),  x = D_mu r,  y = rho_N D_mu^-1 (u + g(u)),
// with D_mu = diag(mu, 1, ..., 1), which maps K_mu onto the Lorentz cone L^D
// and K_mu* onto L^D up to the factor mu (cone/jordan_algebra.hpp), and
// x^T y = rho_N r^T u~. phi(x, y) = 0 iff L ∋ x ⊥ y ∈ L, i.e. Coulomb's law
// (De Saxce's u~ = u + g(u)). As for the natural map, rho is the scalar rho_N.
//
// Jacobian (Fukushima, Luo & Tseng 2002, sec. 5): with w = x o x + y o y and
// s = w^{1/2}, d s = L(s)^-1 (L(x) dx + L(y) dy) where s is in int L, so
//   dphi = (I - L(s)^-1 L(x)) dx + (I - L(s)^-1 L(y)) dy.
// L(s)^-1 in the spectral frame of w (c_{1,2} = (1, -+n)/2, n = w_T/||w_T||):
//   L(s)^-1 = P1/sigma1 + P2/sigma2 + P0/s0,  sigma_i = sqrt(lambda_i(w)),
//   P1 = 2 c1 c1^T, P2 = 2 c2 c2^T, P0 = [0, 0; 0, I - n n^T], s0 = (sigma1 + sigma2)/2.
// Kinks: on bd L \ {0} (sigma1 = 0) x and y lie on the ray (1, n), P1 L(x) =
// P1 L(y) = 0, and dropping the P1 term gives the limit of the Jacobians of
// the smoothed function (w + eps^2 e)^{1/2} as eps -> 0 (its Jacobian
// consistency, Fukushima, Luo & Tseng 2002 sec. 5). At w = 0 the element is
// L(s)^-1 L(x) = L(s)^-1 L(y) = I/sqrt(2), the limit along x = y = t e.
// mu = 0 (K = the normal ray): G = (phi(r_N, rho_N u_N), r_T), scalar phi.
#pragma once

#include <fcsolve/cone/jordan_algebra.hpp>
#include <fcsolve/formulation/one_contact_function.hpp>
#include <fcsolve/formulation/projection_jacobians.hpp>

#include <cmath>

namespace fcsolve {
namespace detail {

inline constexpr double kSqrtHalf = 0.70710678118654752440;  // 1/sqrt(2)

/// Scalar Fischer-Burmeister a + b - sqrt(a^2 + b^2) and its gradient
/// (at a = b = 0 the B-subdifferential element 1 - 1/sqrt(2) for both).
inline double scalar_fischer_burmeister(double a, double b, double* da, double* db) {
  const double h = std::hypot(a, b);
  if (da) {
    *da = h > 0 ? 1 - a / h : 1 - kSqrtHalf;
    *db = h > 0 ? 1 - b / h : 1 - kSqrtHalf;
  }
  return a + b - h;
}

/// phi(x, y) in L^D and, if Vx is non-null, Vx = L(s)^-1 L(x), Vy = L(s)^-1 L(y)
/// (so dphi = (I - Vx) dx + (I - Vy) dy).
template <int D>
SmallVector<D> lorentz_fischer_burmeister(const SmallVector<D>& x, const SmallVector<D>& y,
                                          SmallMatrix<D>* Vx, SmallMatrix<D>* Vy) {
  const SmallVector<D> w = jordan::product<D>(x, x) + jordan::product<D>(y, y);
  const jordan::Spectral<D> sw = jordan::spectral<D>(w);
  const double sigma1 = std::sqrt(std::max(sw.lambda1, 0.0));
  const double sigma2 = std::sqrt(std::max(sw.lambda2, 0.0));
  const SmallVector<D> s = sigma1 * sw.c1 + sigma2 * sw.c2;
  if (Vx) {
    if (sigma2 <= 0) {  // w = 0: x = y = 0
      Vx->setIdentity();
      *Vx *= kSqrtHalf;
      *Vy = *Vx;
    } else {
      const SmallVector<D> c1 = sw.c1, c2 = sw.c2;
      SmallMatrix<D> Linv = (2 / sigma2) * c2 * c2.transpose();
      if (sigma1 > 1e-8 * sigma2) Linv += (2 / sigma1) * c1 * c1.transpose();
      const SmallVector<D - 1> n = 2 * c2.template tail<D - 1>();  // unit: w_T/||w_T||
      Linv.template block<D - 1, D - 1>(1, 1) +=
          (2 / (sigma1 + sigma2)) * (SmallMatrix<D - 1>::Identity() - n * n.transpose());
      Vx->noalias() = Linv * jordan::arrow<D>(x);
      Vy->noalias() = Linv * jordan::arrow<D>(y);
    }
  }
  return x + y - s;
}

}  // namespace detail

/// The SOCCP Fischer-Burmeister function and its Jacobian element, one contact
/// (interface: one_contact_function.hpp).
template <class Cone_>
struct FischerBurmeisterFunction : OneContactFunction<FischerBurmeisterFunction<Cone_>, Cone_> {
  FCSOLVE_ONE_CONTACT_POLICY(Cone_, "fischer-burmeister");

  static void evaluate(const Vec& r, const Vec& u, double mu, const Vec& rho, Vec& G, Mat* A,
                       Mat* B) {
    constexpr int D = Cone::dim;
    const double rho_n = rho[0];
    if (D == 1 || mu == 0) {
      double da = 0, db = 0;
      G = r;  // tangential part (mu = 0): r_T = 0
      G[0] = detail::scalar_fischer_burmeister(r[0], rho_n * u[0], A ? &da : nullptr, &db);
      if (A) {
        A->setZero();
        B->setIdentity();
        (*A)(0, 0) = rho_n * db;
        (*B)(0, 0) = da;
      }
      return;
    }
    if constexpr (D >= 2) {
      const Vec x = jordan::to_lorentz<D>(r, mu);
      const Vec y = rho_n * jordan::dual_to_lorentz<D>(Vec(Cone::modified_velocity(u, mu)), mu);
      if (!A) {
        G = detail::lorentz_fischer_burmeister<D>(x, y, nullptr, nullptr);
        return;
      }
      Mat Vx, Vy;
      G = detail::lorentz_fischer_burmeister<D>(x, y, &Vx, &Vy);
      // B = (I - Vx) D_mu: scale column 0 by mu; A = rho (I - Vy) D_mu^-1 (I + Dg).
      *B = Mat::Identity() - Vx;
      B->col(0) *= mu;
      Mat Iy = Mat::Identity() - Vy;
      Iy.col(0) /= mu;
      A->noalias() = rho_n * Iy * modified_velocity_jacobian<D>(u, mu);
    }
  }
};

}  // namespace fcsolve
