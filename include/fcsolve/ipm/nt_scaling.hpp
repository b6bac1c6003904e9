// Per-contact operations of the interior-point methods, in the Jordan algebra
// of the Lorentz cone L^d (cone/jordan_algebra.hpp):
//
//  * the Coulomb cone K_mu and its dual mapped onto L^d (Acary, Cadoux,
//    Lemarechal & Malick 2011, sec. 3):  y = D r,  x = D^-1 u~,
//    D = diag(mu, 1, ..., 1), so r in K_mu <=> y in L, u~ in K_mu* <=> x in L
//    and r^T u~ = y^T x. The De Saxce shift A s = (mu s, 0, 0) becomes s e.
//  * the Nesterov-Todd scaling of an interior pair (x, y): the symmetric
//    positive definite T with T^-1 x = T y = lambda (Nesterov & Todd 1997).
//    With J = diag(1, -1, ..., -1), det z = z^T J z, the normalised points
//    xn = x / sqrt(det x), yn = y / sqrt(det y), gamma = sqrt((1 + xn^T yn) / 2)
//    and w = (xn + J yn) / (2 gamma) (det w = 1):
//      T = beta [ w0  w1^T ; w1  I + w1 w1^T / (1 + w0) ],
//      T^-1 = J T J / beta^2,   beta = (det x / det y)^(1/4),
//      lambda = (det x det y)^(1/4) Tn yn   (Tn = T / beta)
//    (Vandenberghe, "The CVXOPT linear and quadratic cone program solvers",
//    2010, sec. 4.3; Tn is the quadratic representation P(w^(1/2))).
//  * the Jordan quotient lambda \ r (solve lambda o z = r) and the largest
//    step keeping z + alpha dz in L.
#pragma once

#include <fcsolve/cone/jordan_algebra.hpp>

#include <cmath>
#include <limits>

namespace fcsolve {
namespace ipm {

template <int D>
using Vec = jordan::Vec<D>;
template <int D>
using Mat = jordan::Mat<D>;

/// det z = z0^2 - ||z1||^2, factored to limit cancellation near the boundary.
template <int D>
double lorentz_det(const Vec<D>& z) {
  const double nb = z.template tail<D - 1>().norm();
  return (z[0] - nb) * (z[0] + nb);
}

/// Smallest spectral value z0 - ||z1|| (>= 0 iff z in L).
template <int D>
double lorentz_min_eigenvalue(const Vec<D>& z) {
  return z[0] - z.template tail<D - 1>().norm();
}

/// The NT scaling of one contact: T, T^-1 and the scaled point lambda.
template <int D>
struct NtScaling {
  Mat<D> T, Tinv;
  Vec<D> lambda;

  /// Computes the scaling of (x, y); false if either is not in int L.
  bool compute(const Vec<D>& x, const Vec<D>& y) {
    const double dx = lorentz_det<D>(x), dy = lorentz_det<D>(y);
    if (!(dx > 0 && dy > 0 && x[0] > 0 && y[0] > 0)) return false;
    const double sx = std::sqrt(dx), sy = std::sqrt(dy);
    const Vec<D> xn = x / sx, yn = y / sy;
    const double gamma = std::sqrt(0.5 * (1 + xn.dot(yn)));
    Vec<D> w = xn;
    w[0] += yn[0];
    w.template tail<D - 1>() -= yn.template tail<D - 1>();
    w /= 2 * gamma;
    Mat<D> Tn;
    Tn(0, 0) = w[0];
    Tn.template block<1, D - 1>(0, 1) = w.template tail<D - 1>().transpose();
    Tn.template block<D - 1, 1>(1, 0) = w.template tail<D - 1>();
    Tn.template block<D - 1, D - 1>(1, 1) =
        Mat<D - 1>::Identity() +
        w.template tail<D - 1>() * w.template tail<D - 1>().transpose() / (1 + w[0]);
    const double beta = std::sqrt(sx / sy);
    T = beta * Tn;
    Tinv = Tn / beta;  // J Tn J: flip the signs of the off-diagonal row/column
    Tinv.template block<1, D - 1>(0, 1) *= -1;
    Tinv.template block<D - 1, 1>(1, 0) *= -1;
    lambda = std::sqrt(sx * sy) * (Tn * yn);
    lambda[0] = std::sqrt(sx * sy) * gamma;  // exact first entry (CVXOPT sec. 4.3)
    return true;
  }
};

/// z with lambda o z = r, lambda in int L (arrow(lambda)^-1 r in closed form).
template <int D>
Vec<D> jordan_quotient(const Vec<D>& lambda, const Vec<D>& r) {
  const auto l1 = lambda.template tail<D - 1>();
  Vec<D> z;
  z[0] = (lambda[0] * r[0] - l1.dot(r.template tail<D - 1>())) / lorentz_det<D>(lambda);
  z.template tail<D - 1>() = (r.template tail<D - 1>() - z[0] * l1) / lambda[0];
  return z;
}

/// sup { alpha >= 0 : z + alpha d in L } for z in int L (+inf if unbounded).
/// rho = P(z^-1/2) d maps the question to e + alpha rho in L, whose smallest
/// spectral value is 1 + alpha (rho0 - ||rho1||) (Alizadeh & Goldfarb 2003).
template <int D>
double max_step_in_cone(const Vec<D>& z, const Vec<D>& d) {
  const Vec<D> root_inverse = jordan::sqrt<D>(jordan::inverse<D>(z));
  const Vec<D> rho = jordan::quadratic_representation<D>(root_inverse) * d;
  const double slope = rho.template tail<D - 1>().norm() - rho[0];
  return slope > 0 ? 1 / slope : std::numeric_limits<double>::infinity();
}

}  // namespace ipm
}  // namespace fcsolve
