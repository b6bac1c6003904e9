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
#include <fcsolve/local/polynomial_roots.hpp>

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

  /// Halley's method on th from direction t (updated in place; Halley
  /// 1694, e.g. Press et al., Numerical Recipes, 3rd ed., sec. 9.4):
  ///   dth = -2 f f' / (2 f'^2 - f f''),
  /// cubic where Newton (-f / f') is quadratic: a sliding contact of an NSGS
  /// sweep starts 1e-2 to 1e-6 off its root, which Newton took 3.6 steps to
  /// settle on average (bench_nsgs nsgs-small/cube-3: 17 of its 20 visits
  /// slide); f'' costs five products. The step is taken as the rotation by
  /// 2 atan(dth / 2) (the Cayley transform of the half step): the same to
  /// third order, never more than a half turn, and exactly of unit length
  /// with one division and no square root. With dth / 2 = N / D,
  /// N = -2 f f', D = 2 (2 f'^2 - f f''),
  ///   t+ = ((D^2 - N^2) t + 2 N D J t) / (D^2 + N^2),   J t = (-s, c).
  /// Stops after a step |dth| <= `tol`, or when the error left after the
  /// step, K |dth|^3 with Halley's constant K = f''^2 / (4 f'^2) -
  /// f''' / (6 f') (plus 1/12 for the rotation) bounded through the
  /// coefficients, is at most `settled` (radians; default: rounding level).
  /// Returns false if the denominator vanishes or the iteration does not
  /// settle.
  bool halley(Vec2& t, int max_iter, double tol = 1e-9, double settled = 1e-17) const {
    // |f''| <= m2 and |f'''| <= m3 at every unit t
    const double m2 = std::abs(a1) + std::abs(a2) + 2 * (std::abs(C - A) + std::abs(B));
    const double m3 = std::abs(a1) + std::abs(a2) + 4 * (std::abs(C - A) + std::abs(B));
    const double rounding = settled;
    for (int it = 0; it < max_iter; ++it) {
      const double c = t[0], s = t[1], cc = c * c, ss = s * s, cs = c * s;
      const double f = a1 * s - a2 * c + A * cc + B * cs + C * ss;
      const double df = a1 * c + a2 * s + 2 * (C - A) * cs + B * (cc - ss);
      const double d2f = a2 * c - a1 * s + 2 * (C - A) * (cc - ss) - 4 * B * cs;
      const double N = -2 * f * df, D = 2 * (2 * df * df - f * d2f);
      if (D == 0 || !std::isfinite(D) || !std::isfinite(N)) return false;
      const double DD = D * D, NN = N * N, ND2 = 2 * N * D;
      const double h = 1 / (DD + NN);
      t = Vec2(((DD - NN) * c - ND2 * s) * h, ((DD - NN) * s + ND2 * c) * h);
      const double step2 = 4 * NN * h;  // dth^2 / (1 + dth^2 / 4)
      if (step2 <= tol * tol) return true;
      // K f'^2 <= k: stop when k |dth|^3 <= rounding f'^2 (squared: no root)
      const double adf = std::abs(df), k = 0.25 * m2 * m2 + m3 * adf * (1.0 / 6) + df * df * (1.0 / 12);
      if (k * k * step2 * step2 * step2 <= rounding * rounding * adf * adf * adf * adf) return true;
    }
    return false;
  }

  /// Every root direction: the quartic's real roots (local/polynomial_roots.hpp)
  /// and th = pi, each polished by Halley on f. Returns how many of `out`
  /// were written (at most 5, or 4 axes when f = 0).
  int roots(std::array<Vec2, 5>& out, int polish_iter) const {
    Polynomial p;  // coefficients of tau^0 ... tau^4
    p.c = {A - a2, 2 * (a1 + B), 4 * C - 2 * A, 2 * (a1 - B), a2 + A};
    p.degree = 4;
    int n = 0;
    out[n++] = Vec2(-1, 0);  // th = pi
    if (std::all_of(p.c.begin(), p.c.end(), [](double x) { return x == 0; })) {
      out[n++] = Vec2(1, 0);  // f = 0 everywhere: try the axes
      out[n++] = Vec2(0, 1);
      out[n++] = Vec2(0, -1);
      return n;
    }
    std::array<double, 4> tau;
    const int count = real_roots(p, tau);
    for (int i = 0; i < count; ++i) {
      if (std::abs(tau[i]) <= 1) {
        out[n++] = Vec2(1 - tau[i] * tau[i], 2 * tau[i]) / (1 + tau[i] * tau[i]);
      } else {  // same formula in 1 / tau, safe for huge tau
        const double v = 1 / tau[i];
        out[n++] = Vec2(v * v - 1, 2 * v) / (v * v + 1);
      }
    }
    for (int k = 0; k < n; ++k) {
      Vec2 t = out[k];
      if (halley(t, polish_iter) && std::abs(value(t)) <= std::abs(value(out[k]))) out[k] = t;
    }
    return n;
  }
};

}  // namespace local
}  // namespace fcsolve
