// The sliding branch of the 3D one-contact problem as one equation in the
// sliding direction (derivation written out here; it is the "quartic" of the
// exact local solver, Acary, Bremond & Huber 2018, sec. 4.3 [NSGS-EXACT]).
//
// Sliding means u_N = 0, r = r_N (1, -mu t) with t = u_T / ||u_T|| a unit
// vector of the tangent plane. With t = (c, s) = (cos th, sin th) and
//   W = [ w  n^T ; m  T ]   (w = W_NN, n = W_NT, m = W_TN, T = W_TT 2 x 2),
// the normal equation w r_N - mu r_N n.t + q_N = 0 gives
//   r_N(t) = -q_N / (w - mu n.t),
// and u_T = r_N (m - mu T t) + q_T must be a positive multiple of t:
// u_T x t = 0 with u_T . t > 0. Multiplied by the denominator,
//   f(t) = a1 s - a2 c + A c^2 + B c s + C s^2,
//   a = w q_T - q_N m,
//   A = mu (n1 q_T2 - q_N T21),   C = mu (q_N T12 - n2 q_T1),
//   B = mu (q_N (T11 - T22) - n1 q_T1 + n2 q_T2),
// a trigonometric polynomial of degree 2. With tau = tan(th / 2), c = (1 -
// tau^2) / (1 + tau^2), s = 2 tau / (1 + tau^2), (1 + tau^2)^2 f is the quartic
//   (a2 + A) tau^4 + 2 (a1 - B) tau^3 + (4 C - 2 A) tau^2 + 2 (a1 + B) tau + (A - a2),
// whose roots miss only th = pi (tau = inf).
#pragma once

#include <fcsolve/core/types.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>

namespace fcsolve {
namespace local {

struct SlidingEquation {
  using Vec2 = Eigen::Vector2d;
  double a1 = 0, a2 = 0, A = 0, B = 0, C = 0;

  SlidingEquation() = default;
  SlidingEquation(const SmallMatrix<3>& W, const SmallVector<3>& q, double mu) {
    const double qn = q[0], p1 = q[1], p2 = q[2], n1 = W(0, 1), n2 = W(0, 2);
    a1 = W(0, 0) * p1 - qn * W(1, 0);
    a2 = W(0, 0) * p2 - qn * W(2, 0);
    A = mu * (n1 * p2 - qn * W(2, 1));
    B = mu * (qn * (W(1, 1) - W(2, 2)) - n1 * p1 + n2 * p2);
    C = mu * (qn * W(1, 2) - n2 * p1);
  }

  /// f(t), t = (c, s) a unit vector
  double value(const Vec2& t) const {
    const double c = t[0], s = t[1];
    return a1 * s - a2 * c + A * c * c + B * c * s + C * s * s;
  }
  /// df/dth at t
  double derivative(const Vec2& t) const {
    const double c = t[0], s = t[1];
    return a1 * c + a2 * s + 2 * (C - A) * c * s + B * (c * c - s * s);
  }

  /// The sliding reaction for direction t (r_N from the normal equation);
  /// non-finite when the denominator vanishes.
  static SmallVector<3> reaction(const SmallMatrix<3>& W, const SmallVector<3>& q, double mu,
                                 const Vec2& t) {
    const double rn = -q[0] / (W(0, 0) - mu * (W(0, 1) * t[0] + W(0, 2) * t[1]));
    return SmallVector<3>(rn, -mu * rn * t[0], -mu * rn * t[1]);
  }

  /// Newton on th from direction t (updated in place). The step dth =
  /// -f / f' is taken as a rotation by atan(dth): the same to third order, so
  /// still quadratic, and never more than a quarter turn. Stops after a step
  /// below `tol` (quadratic convergence: the next one would be at rounding
  /// level). Returns false if f' vanishes or the iteration does not settle.
  bool newton(Vec2& t, int max_iter, double tol = 1e-9) const {
    for (int it = 0; it < max_iter; ++it) {
      const double df = derivative(t);
      if (df == 0 || !std::isfinite(df)) return false;
      const double step = -value(t) / df;
      const double h = 1 / std::sqrt(1 + step * step);
      t = Vec2(t[0] - step * t[1], t[1] + step * t[0]) * h;
      if (std::abs(step) <= tol) return true;
    }
    return false;
  }

  /// Every root direction: the real parts of the quartic's roots (companion
  /// matrix eigenvalues) and th = pi, each polished by Newton. Returns how
  /// many of `out` were written (at most 5, or 4 axes when f = 0).
  int roots(std::array<Vec2, 5>& out, int polish_iter) const {
    const std::array<double, 5> c = {a2 + A, 2 * (a1 - B), 4 * C - 2 * A, 2 * (a1 + B), A - a2};
    double cmax = 0;
    for (double x : c) cmax = std::max(cmax, std::abs(x));
    int n = 0;
    out[n++] = Vec2(-1, 0);  // th = pi
    if (cmax == 0) {         // f = 0 everywhere: try the axes
      out[n++] = Vec2(1, 0);
      out[n++] = Vec2(0, 1);
      out[n++] = Vec2(0, -1);
      return n;
    }
    int lead = 0;  // vanishing leading coefficients: roots at infinity, th = pi
    while (lead < 4 && std::abs(c[lead]) <= 1e-14 * cmax) ++lead;
    const int degree = 4 - lead;
    if (degree > 0) {
      using Companion = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 4, 4>;
      Companion M = Companion::Zero(degree, degree);
      for (int i = 1; i < degree; ++i) M(i, i - 1) = 1;
      for (int i = 0; i < degree; ++i) M(i, degree - 1) = -c[4 - i] / c[lead];
      Eigen::EigenSolver<Companion> eig(M, /*computeEigenvectors=*/false);
      for (int i = 0; i < degree; ++i) {
        const double tau = eig.eigenvalues()[i].real();
        if (std::abs(tau) <= 1) {
          out[n++] = Vec2(1 - tau * tau, 2 * tau) / (1 + tau * tau);
        } else {  // same formula in 1 / tau, safe for huge tau
          const double v = 1 / tau;
          out[n++] = Vec2(v * v - 1, 2 * v) / (v * v + 1);
        }
      }
    }
    for (int k = 0; k < n; ++k) {
      Vec2 t = out[k];
      if (newton(t, polish_iter) && std::abs(value(t)) <= std::abs(value(out[k]))) out[k] = t;
    }
    return n;
  }
};

}  // namespace local
}  // namespace fcsolve
