// Local solver (e): the exact one-contact solution, by enumeration of the
// three branches of Coulomb's law (the EXACT local solver of Acary, Bremond &
// Huber 2018, sec. 4.3):
//
//   take-off  r = 0                     a solution iff q_N >= 0
//   stick     r = -W^-1 q, u = 0        a solution iff r ∈ K
//   slide     u_N = 0, r = r_N (1, -mu t), t = u_T / ||u_T||
//
// 3D sliding: the roots of one equation in the direction t
// (local/sliding_equation.hpp, a quartic). 2D: t = +-1, two closed-form
// candidates. Frictionless: r = max(0, -q / W). mu = 0: r = (max(0, -q_N / W_NN), 0).
//
// A candidate counts as a solution only if its natural-map residual
// ||r - P_K(r - (u + g(u)))|| is at rounding level: the residual is the
// ground truth, so no branch test needs a tolerance of its own.
//
// Two modes. Reference (newton_first = false): enumerate every solution and
// return the one closest to the warm start; this validates the other local
// solvers (several solutions exist for large mu or unsymmetric W). Fast
// (newton_first = true, the default): take-off, then stick, then Halley's
// method on the sliding direction from the warm start's direction
// (SlidingEquation::halley); the companion matrix (a 4 x 4 eigenvalue
// problem) only when that iteration fails.
#pragma once

#include <fcsolve/core/compiler.hpp>
#include <fcsolve/local/one_contact.hpp>
#include <fcsolve/local/sliding_equation.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace fcsolve {
namespace local {

template <class Cone_>
struct Enumerative {
  FCSOLVE_ONE_CONTACT_POLICY(Cone_, "enumerative");
  static constexpr int kMaxSolutions = 8;

  struct Settings {
    bool newton_first = true;  ///< fast mode (see the header comment)
    double tol = 1e-9;         ///< solution iff ||F_nat|| <= tol * scale
    int newton_iter = 30;      ///< (Halley) steps on the sliding direction
  };
  struct Data {
    Mat W, W_inv;
    double W_norm = 0;  ///< Frobenius norm, the scale of the residual test
    bool invertible = false;
    double mu = 0;
  };
  /// Every solution found, without duplicates.
  struct Solutions {
    std::array<Vec, kMaxSolutions> r;
    std::array<ContactCase, kMaxSolutions> kind;
    int count = 0;
  };

  static Data prepare(const Mat& W, double mu, const Settings&) {
    Data d;
    d.W = W;
    d.W_norm = W.norm();
    d.mu = mu;
    d.W_inv = OneContact<Cone>::inverse_or_zero(W);
    d.invertible = !d.W_inv.isZero(0);
    return d;
  }

  /// True if r solves the one-contact problem to rounding level.
  static bool is_solution(const Data& d, const Vec& q, const Vec& r, const Settings& s) {
    if (!r.allFinite()) return false;
    const double scale = std::max({q.norm(), d.W_norm * r.norm(), 1e-300});
    return OneContact<Cone>::residual(d.W, q, d.mu, r) <= s.tol * scale;
  }

  /// Every solution of the three branches.
  static Solutions enumerate(const Data& d, const Vec& q, const Settings& s) {
    Solutions out;
    const auto consider = [&](const Vec& r, ContactCase kind) {
      if (out.count == kMaxSolutions || !is_solution(d, q, r, s)) return;
      for (int k = 0; k < out.count; ++k)
        if ((out.r[k] - r).norm() <= 1e-8 * std::max(r.norm(), 1e-300)) return;
      out.r[out.count] = r;
      out.kind[out.count] = kind;
      ++out.count;
    };
    consider(Vec::Zero(), ContactCase::TakeOff);
    if (d.invertible) consider(Vec(-d.W_inv * q), ContactCase::Stick);
    if constexpr (dim == 2) {
      if (d.mu == 0) {
        consider(normal_only(d, q), ContactCase::Slide);
      } else {
        for (const double t : {1.0, -1.0}) {
          const double rn = -q[0] / (d.W(0, 0) - d.mu * d.W(0, 1) * t);
          consider(Vec(rn, -d.mu * rn * t), ContactCase::Slide);
        }
      }
    } else if constexpr (dim == 3) {
      if (d.mu == 0) {
        consider(normal_only(d, q), ContactCase::Slide);
      } else {
        std::array<SlidingEquation::Vec2, 5> t;
        const SlidingEquation f(d.W, q, d.mu);
        const int n = f.roots(t, s.newton_iter);
        for (int k = 0; k < n; ++k)
          consider(SlidingEquation::reaction(d.W, q, d.mu, t[k]), ContactCase::Slide);
      }
    }
    return out;
  }

  /// Both paths return only the branch taken (Unknown: none), and the
  /// result is built once from it: when the fast path's LocalResult and the
  /// enumeration's met at one return, GCC assembled it on the stack by two
  /// narrow stores and read it back by one wide load, a store-forwarding
  /// stall that perf put at 13-20 % of a local solve (bench_nsgs
  /// nsgs-small/cube-3, a sphere pile of 10^4 contacts).
  FCSOLVE_ALWAYS_INLINE static LocalResult solve(const Data& d, const Vec& q, Vec& r, const Settings& s) {
    ContactCase kind = s.newton_first ? fast_solve(d, q, r, s) : ContactCase::Unknown;
    if (kind == ContactCase::Unknown) kind = solve_by_enumeration(d, q, r, s);
    return LocalResult{1, kind != ContactCase::Unknown, kind};
  }

 private:
  /// Every solution (enumerate()), then the one closest to the warm start r;
  /// Unknown (r untouched) when there is none. Out of line: it is the rare
  /// path, and inlined its size kept the fast path out of the sweep.
  FCSOLVE_NOINLINE static ContactCase solve_by_enumeration(const Data& d, const Vec& q, Vec& r,
                                                           const Settings& s) {
    const Solutions sol = enumerate(d, q, s);
    if (sol.count == 0) return ContactCase::Unknown;
    int best = 0;
    for (int k = 1; k < sol.count; ++k)
      if ((sol.r[k] - r).norm() < (sol.r[best] - r).norm()) best = k;
    r = sol.r[best];
    return sol.kind[best];
  }

  /// r = (max(0, -q_N / W_NN), 0): the solution family when mu = 0.
  static Vec normal_only(const Data& d, const Vec& q) {
    Vec r = Vec::Zero();
    if (d.W(0, 0) > 0) r[0] = std::max(0.0, -q[0] / d.W(0, 0));
    return r;
  }

  /// Take-off, stick, then Halley on the sliding direction; the branch whose
  /// verified solution r now holds, or Unknown (r untouched).
  FCSOLVE_ALWAYS_INLINE static ContactCase fast_solve(const Data& d, const Vec& q, Vec& r, const Settings& s) {
    if (OneContact<Cone>::takes_off(q)) {
      r.setZero();
      return ContactCase::TakeOff;
    }
    if (d.invertible) {
      // OneContact::product: Eigen's went out of line in large translation units
      const Vec stick = -OneContact<Cone>::product(d.W_inv, q);
      if (Cone::contains(stick, d.mu)) {
        r = stick;
        return ContactCase::Stick;
      }
      if constexpr (dim == 3) {
        if (d.mu > 0 && slide_by_direction(d, q, stick, s, r)) return ContactCase::Slide;
      }
    }
    return ContactCase::Unknown;
  }

  /// 3D sliding by Halley's method on the direction, started from the warm
  /// start's sliding direction -r_T / ||r_T|| (or, failing that, from the
  /// stick candidate's). Accepts only a verified solution. f(t) = 0 also
  /// holds where u_T is anti-parallel to t (u_T . t < 0, not a solution);
  /// when the iteration settles on such a root, or does not settle, it is
  /// started once more from the opposite direction -t: a run costs a few
  /// hundred instructions, the quartic fallback tens of thousands
  /// (callgrind, bench_nsgs nsgs-small/cube-4: one fallback a solve was a
  /// quarter of it).
  template <int D = dim, std::enable_if_t<D == 3, int> = 0>
  static bool slide_by_direction(const Data& d, const Vec& q, const Vec& stick, const Settings& s, Vec& r) {
    using Vec2 = SlidingEquation::Vec2;
    Vec2 t(-r[1], -r[2]);
    if (!(r[0] > 0) || t.squaredNorm() == 0) t = Vec2(-stick[1], -stick[2]);
    if (t.squaredNorm() == 0) t = Vec2(q[1], q[2]);
    const double norm = t.norm();
    t = norm > 0 ? Vec2(t / norm) : Vec2(1, 0);
    const SlidingEquation f(d.W, q, d.mu);
    for (int run = 0; run < 2; ++run) {  // one call site: the compiler inlines it
      if (slide_from(f, d, q, s, t, r)) return true;
      t = -t;  // t: where the first run ended
    }
    return false;
  }

  /// Halley on the sliding direction from t (left where it ended); true
  /// (and r set) if it ends on a verified solution. The iteration stops
  /// once the direction's error bound is below kSettledFraction * tol
  /// radians, not at rounding level: the residual test accepts
  /// ||u_T x t|| <= tol * scale, and ||u_T|| <= ||W|| ||r|| + ||q|| <=
  /// 2 scale, so that bound passes it with a margin of 50 (the last
  /// step to rounding level was 6 of the 45 Halley steps of a solve of
  /// bench_nsgs nsgs-small/cube-3, 21 of 132 on cube-4, same sweeps). A
  /// contact still moving is re-solved next sweep from this direction,
  /// within one step of rounding level.
  template <int D = dim, std::enable_if_t<D == 3, int> = 0>
  static bool slide_from(const SlidingEquation& f, const Data& d, const Vec& q, const Settings& s,
                         SlidingEquation::Vec2& t, Vec& r) {
    constexpr double kSettledFraction = 1e-2;
    if (!f.halley(t, s.newton_iter, 1e-9, kSettledFraction * s.tol)) return false;
    const Vec candidate = SlidingEquation::reaction(d.W, q, d.mu, t);
    if (!is_sliding_solution(d, q, candidate, t, s)) return false;
    r = candidate;
    return true;
  }

  /// is_solution() for a candidate of the sliding branch, r = r_N (1, -mu t)
  /// with u_N = 0 by construction (SlidingEquation::reaction): it solves the
  /// problem iff r_N > 0 and u_T = lambda t with lambda > 0 (Coulomb's
  /// sliding law; Acary, Bremond & Huber 2018, sec. 4.3). Then r - (u +
  /// g(u)) = (r_N - mu lambda, -(mu r_N + lambda) t) lies outside K and
  /// projects onto r, so F_nat = 0; off that, ||F_nat|| is of the order of
  /// ||u_T x t|| (u_T's part across t), which is tested against the same
  /// tol * scale. No square root: squares are compared. The natural-map
  /// residual cost about a quarter of a contact visit (callgrind, bench_nsgs
  /// nsgs-small/cube-3).
  template <int D = dim, std::enable_if_t<D == 3, int> = 0>
  static bool is_sliding_solution(const Data& d, const Vec& q, const Vec& r,
                                  const SlidingEquation::Vec2& t, const Settings& s) {
    if (!(r[0] > 0 && std::isfinite(r[0]))) return false;  // then r_T = -mu r_N t is finite too
    const Vec u = OneContact<Cone>::velocity(d.W, q, r);
    const double along = u[1] * t[0] + u[2] * t[1], across = u[1] * t[1] - u[2] * t[0];
    const double scale2 = std::max({q.squaredNorm(), d.W_norm * d.W_norm * r.squaredNorm(), 1e-300});
    const double tol2 = s.tol * s.tol * scale2;
    return along > 0 && across * across + u[0] * u[0] <= tol2;
  }
};

}  // namespace local
}  // namespace fcsolve
