// What the global and local interior-point forms share: the per-contact state
// an iteration computes (NT scaling, subgradient of ||x_T||), the iterate and
// direction vectors, and the error of the problem with a frozen s.
//
// Unknowns in Lorentz coordinates (ipm/nt_scaling.hpp): y = D r, x = D^-1 u~,
// s = the frozen (convex IPM, ACLM) or coupled (NIPM) tangential speeds, and
// for the global form v. The equations (Acary, Cadoux, Lemarechal & Malick
// 2011; Acary 2025 (talk), "NIPM - linearization"; docs/references.md;
// FCLIB signs M v = H r + f):
//   M v - H r - f = 0                          (global only)
//   H^T v + w + A s - u~ = 0   i.e.  x = Hs^T v + D^-1 w + s e   (Hs = H D^-1)
//                              or    x = D^-1 W D^-1 y + D^-1 q + s e (local)
//   s - ||x_T|| = 0                            (coupled s only)
//   x o y = mu e,  x, y in L.
#pragma once

#include <fcsolve/cone/cones.hpp>
#include <fcsolve/ipm/nt_scaling.hpp>
#include <fcsolve/problem/error.hpp>

#include <type_traits>
#include <vector>

namespace fcsolve {
namespace ipm {

/// The Coulomb cone policy of a contact dimension D (2 or 3).
template <int D>
using CoulombCone = std::conditional_t<D == 3, Coulomb3D, Coulomb2D>;

template <int D>
struct ContactState {
  std::vector<NtScaling<D>, Eigen::aligned_allocator<NtScaling<D>>> scaling;
  /// n_a = (0, x_T / ||x_T||): the (sub)gradient of ||x_T|| when s is
  /// coupled (NIPM); zero when s is frozen. P_a = I + e n_a^T.
  std::vector<Vec<D>, Eigen::aligned_allocator<Vec<D>>> normal;
  void resize(Index nc) {
    scaling.resize(std::size_t(nc));
    normal.assign(std::size_t(nc), Vec<D>::Zero());
  }
};

/// A primal-dual point: v (global form only), x, y (Lorentz coordinates), s.
struct Iterate {
  Vector v, x, y, s;
  void resize(Index n, Index m, Index nc) {
    v.setZero(n);
    x.setZero(m);
    y.setZero(m);
    s.setZero(nc);
  }
};

/// Sum over contacts of ||r - P_K(r - u~)||^2 with u~ = u + (mu s, 0, ...):
/// the natural map of the problem with s frozen (ACLM 2011, problem (13)).
template <int D>
double frozen_natural_map_squared(const Vector& r, const Vector& u, const Eigen::Ref<const Vector>& mu,
                                  const Vector& s) {
  using Cone = CoulombCone<D>;
  double sum = 0;
  for (Index a = 0; a < mu.size(); ++a) {
    Vec<D> ut = u.template segment<D>(a * D);
    ut[0] += mu[a] * s[a];
    const Vec<D> ra = r.template segment<D>(a * D);
    sum += (ra - Cone::project(Vec<D>(ra - ut), mu[a])).squaredNorm();
  }
  return sum;
}

/// Squared natural map of (r, u): Coulomb's (core/error.hpp) or, with
/// `frozen`, that of the problem with s frozen.
template <int D>
double natural_map_squared(const Vector& r, const Vector& u, const Eigen::Ref<const Vector>& mu,
                           const Vector& s, bool frozen) {
  return frozen ? frozen_natural_map_squared<D>(r, u, mu, s)
                : natural_map_norms<CoulombCone<D>>(r, u, mu).squared_sum;
}

/// A frictionless contact (mu = 0) in Lorentz coordinates. Its cone K_0 is
/// the normal half-line and K_0* the half-space u_N >= 0, so it keeps the
/// Lorentz block but drops its tangential coupling: D^-1 = diag(1, 0, ..)
/// instead of diag(1/mu, 1, ..), i.e. y_N = r_N, r_T = 0, x_T = 0 and no
/// De Saxce shift (mu s = 0). The block's complementarity x o y = mu e then
/// reduces to x_N y_N = mu with y_T -> 0 on the central path: the normal
/// complementarity r_N >= 0, u_N >= 0, r_N u_N = 0 of the frictionless law.
inline bool frictionless(double mu) { return !(mu > 0); }

/// The diagonal of D^-1, one entry per unknown: (1/mu, 1, ..) per frictional
/// contact, (1, 0, ..) per frictionless one (see frictionless()).
template <int D>
Vector lorentz_inverse_scaling(const Eigen::Ref<const Vector>& mu) {
  Vector dinv = Vector::Ones(mu.size() * D);
  for (Index a = 0; a < mu.size(); ++a) {
    if (frictionless(mu[a])) dinv.template segment<D - 1>(a * D + 1).setZero();
    else dinv[a * D] = 1 / mu[a];
  }
  return dinv;
}

/// r = D^-1 y: the reactions of the Lorentz-coordinate y (r_T = 0 on a
/// frictionless contact).
template <int D>
void reaction_from_lorentz(const Vector& y, const Eigen::Ref<const Vector>& mu, Vector& r) {
  r = y;
  for (Index a = 0; a < mu.size(); ++a) {
    if (frictionless(mu[a])) r.template segment<D - 1>(a * D + 1).setZero();
    else r[a * D] /= mu[a];
  }
}

/// s_a = ||u_T^a||, the tangential speeds of u; 0 on a frictionless contact,
/// where the De Saxce shift mu s vanishes whatever s is.
template <int D>
Vector tangential_speeds(const Vector& u, const Eigen::Ref<const Vector>& mu) {
  Vector s(mu.size());
  for (Index a = 0; a < s.size(); ++a)
    s[a] = frictionless(mu[a]) ? 0.0 : u.template segment<D - 1>(a * D + 1).norm();
  return s;
}

/// Adds s_a to the normal entry of each contact block of z (z += s e): the
/// shift that moves a point into the interior of the cones.
template <int D>
void add_normal(Vector& z, const Vector& s) {
  for (Index a = 0; a < s.size(); ++a) z[a * D] += s[a];
}

/// z += E s, E the De Saxce shift in Lorentz coordinates: s_a on the normal
/// entry of a frictional contact (u~_N / mu = u_N / mu + s), nothing on a
/// frictionless one (mu s = 0).
template <int D>
void add_friction_shift(Vector& z, const Vector& s, const Eigen::Ref<const Vector>& mu) {
  for (Index a = 0; a < s.size(); ++a)
    if (!frictionless(mu[a])) z[a * D] += s[a];
}

/// dz_a += e (n_a . dz_a): applies P = I + e n^T contact by contact.
template <int D>
void apply_coupling(const ContactState<D>& cs, Vector& z) {
  for (std::size_t a = 0; a < cs.normal.size(); ++a)
    z[Index(a) * D] += cs.normal[a].dot(z.template segment<D>(Index(a) * D));
}

}  // namespace ipm
}  // namespace fcsolve
