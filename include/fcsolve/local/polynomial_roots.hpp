// Real roots of a polynomial of degree <= 4, by derivative bracketing: the
// real roots of p are separated by those of p' (Rolle), so the roots of the
// derivatives, found recursively down to a linear one, cut the real line
// into intervals where p is monotone, each holding at most one root, found
// by safeguarded Newton-bisection (Press et al., Numerical Recipes, "rtsafe").
// Roots lie within the Cauchy bound 1 + max_i |c_i / c_n|. A double root
// (p touches zero without changing sign) is a root of p' where |p| is at
// rounding level, and is kept too.
// No eigenvalue solver: the companion-matrix route costs several seconds of
// compile time per translation unit for one 4 x 4 Hessenberg-Schur.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace fcsolve {
namespace local {

/// Polynomial c[0] + c[1] x + ... + c[n] x^n (n <= 4).
struct Polynomial {
  std::array<double, 5> c{};
  int degree = 0;

  double value(double x) const {
    double v = c[degree];
    for (int i = degree - 1; i >= 0; --i) v = v * x + c[i];
    return v;
  }
  Polynomial derivative() const {
    Polynomial d;
    d.degree = std::max(degree - 1, 0);
    for (int i = 1; i <= degree; ++i) d.c[i - 1] = i * c[i];
    if (degree == 0) d.c[0] = 0;
    return d;
  }
  /// Drops leading coefficients below `relative` times the largest one.
  void trim(double relative = 1e-14) {
    double cmax = 0;
    for (int i = 0; i <= degree; ++i) cmax = std::max(cmax, std::abs(c[i]));
    while (degree > 0 && std::abs(c[degree]) <= relative * cmax) --degree;
  }
};

namespace detail {

/// max(1, |x|)^n (the size of the terms of p at x), without std::pow.
inline double power_scale(double x, int n) {
  const double ax = std::max(1.0, std::abs(x));
  double v = 1;
  for (int i = 0; i < n; ++i) v *= ax;
  return v;
}

/// The root of the monotone p on [lo, hi] with p(lo) p(hi) <= 0.
inline double bracketed_root(const Polynomial& p, const Polynomial& dp, double lo, double hi) {
  double flo = p.value(lo);
  if (flo == 0) return lo;
  if (p.value(hi) == 0) return hi;
  double x = 0.5 * (lo + hi);
  for (int it = 0; it < 200 && lo < hi; ++it) {
    const double fx = p.value(x), dfx = dp.value(x);
    if (fx == 0) return x;
    if ((fx < 0) == (flo < 0)) {
      lo = x;
      flo = fx;
    } else {
      hi = x;
    }
    const double newton = dfx != 0 ? x - fx / dfx : lo;
    const double next = newton > lo && newton < hi ? newton : 0.5 * (lo + hi);
    if (next == x || std::abs(next - x) <= 1e-16 * std::max(1.0, std::abs(x))) return next;
    x = next;
  }
  return x;
}

}  // namespace detail

/// The real roots of p, increasing; returns how many were written (<= 4).
inline int real_roots(Polynomial p, std::array<double, 4>& roots) {
  p.trim();
  if (p.degree == 0) return 0;
  if (p.degree == 1) {
    roots[0] = -p.c[0] / p.c[1];
    return 1;
  }
  const Polynomial dp = p.derivative();
  std::array<double, 4> critical;
  const int nc = real_roots(dp, critical);
  double bound = 0;
  for (int i = 0; i < p.degree; ++i) bound = std::max(bound, std::abs(p.c[i] / p.c[p.degree]));
  bound += 1;
  // interval ends: -bound, the critical points inside (-bound, bound), bound
  std::array<double, 6> ends;
  int ne = 0;
  ends[ne++] = -bound;
  for (int i = 0; i < nc; ++i)
    if (critical[i] > -bound && critical[i] < bound) ends[ne++] = critical[i];
  ends[ne++] = bound;
  double scale = 0;  // rounding level of p near its roots
  for (int i = 0; i <= p.degree; ++i) scale = std::max(scale, std::abs(p.c[i]));
  int n = 0;
  for (int i = 0; i + 1 < ne && n < 4; ++i) {
    const double a = ends[i], b = ends[i + 1], fa = p.value(a), fb = p.value(b);
    if ((fa <= 0 && fb >= 0) || (fa >= 0 && fb <= 0)) {
      const double x = detail::bracketed_root(p, dp, a, b);
      if (n == 0 || x > roots[n - 1]) roots[n++] = x;
    } else if (i > 0 && std::abs(fa) <= 1e-12 * scale * detail::power_scale(a, p.degree)) {
      if (n == 0 || a > roots[n - 1]) roots[n++] = a;  // a double root at a critical point
    }
  }
  return n;
}

}  // namespace local
}  // namespace fcsolve
