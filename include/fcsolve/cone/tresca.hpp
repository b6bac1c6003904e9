// The convex sets of the fixed-point splittings of Coulomb friction
// (fixed_point/): the threshold s >= 0 of a contact takes the place of mu.
//   TrescaCylinder<D>  C(s) = { r in R^D : r_N >= 0, ||r_T|| <= s }  (D = 2, 3)
//   FrictionDisc<D>    D(s) = { r_T in R^D : ||r_T|| <= s }           (D = 1, 2)
// Tresca's law is the variational inequality -u in N_C(s)(r), u = W r + q:
// Coulomb's law with the radius mu r_N frozen at s (Acary, Bremond & Huber
// 2018, sec. on the Tresca and Panagiotopoulos fixed points). No De Saxce
// shift: the natural map r - P_C(r - u) is the problem's own residual, so
// NSGS and problem/error.hpp measure a Tresca (disc) problem through these
// policies unchanged.
// The sets are not cones for s > 0: project_dual (Moreau's z + P(-z), the
// projection on the dual cone when s = 0) exists for the cone-policy check
// (cone/cones.hpp) and nothing in the fixed points uses it.
#pragma once

#include <fcsolve/cone/frictionless.hpp>
#include <fcsolve/core/types.hpp>

#include <algorithm>
#include <cmath>

namespace fcsolve {
namespace detail {
/// z clipped to the ball of radius s (s >= 0).
template <class V, class Scalar>
V clip_to_ball(const V& z, Scalar s) {
  const Scalar n = z.norm();
  return n <= s ? z : V(z * (n > 0 ? s / n : Scalar(0)));
}
}  // namespace detail

/// R_+^N x B(s): N = 1 normal component kept >= 0 (the cylinder), N = 0
/// (the disc), then D - N components in the ball of radius s.
template <int D, int N, class Scalar_ = double>
struct ThresholdSet {
  static_assert(D - N >= 1 && (N == 0 || N == 1), "a ball of 1 or 2 components after 0 or 1 normal");
  using Scalar = Scalar_;
  static constexpr int dim = D;
  using Vec = SmallVector<D, Scalar>;
  static Vec project(const Vec& z, Scalar s) {
    Vec p;
    if constexpr (N == 1) p[0] = std::max(z[0], Scalar(0));
    p.template tail<D - N>() = detail::clip_to_ball(SmallVector<D - N, Scalar>(z.template tail<D - N>()), s);
    return p;
  }
  static Vec project_dual(const Vec& z, Scalar s) { return z + project(Vec(-z), s); }
  static Vec de_saxce_shift(const Vec&, Scalar) { return Vec::Zero(); }
  static Vec modified_velocity(const Vec& u, Scalar) { return u; }
  static bool contains(const Vec& r, Scalar s, Scalar tol = 0) { return (r - project(r, s)).norm() <= tol; }
};

template <int D, class Scalar = double>
using TrescaCylinder = ThresholdSet<D, 1, Scalar>;
template <int D, class Scalar = double>
using FrictionDisc = ThresholdSet<D, 0, Scalar>;

/// The Tresca set of a cone policy: the cylinder of its dimension, and
/// R_+ itself (no threshold) for frictionless contact.
template <class Cone>
struct tresca_set {
  using type = TrescaCylinder<Cone::dim, typename Cone::Scalar>;
};
template <class Scalar>
struct tresca_set<FrictionlessTpl<Scalar>> {
  using type = FrictionlessTpl<Scalar>;
};
template <class Cone>
using tresca_set_t = typename tresca_set<Cone>::type;

}  // namespace fcsolve
