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

/// r = D^-1 y: the reactions of the Lorentz-coordinate y.
template <int D>
void reaction_from_lorentz(const Vector& y, const Eigen::Ref<const Vector>& mu, Vector& r) {
  r = y;
  for (Index a = 0; a < mu.size(); ++a) r[a * D] /= mu[a];
}

/// Adds s_a to the normal entry of each contact block of z (z += E s).
template <int D>
void add_normal(Vector& z, const Vector& s) {
  for (Index a = 0; a < s.size(); ++a) z[a * D] += s[a];
}

/// dz_a += e (n_a . dz_a): applies P = I + e n^T contact by contact.
template <int D>
void apply_coupling(const ContactState<D>& cs, Vector& z) {
  for (std::size_t a = 0; a < cs.normal.size(); ++a)
    z[Index(a) * D] += cs.normal[a].dot(z.template segment<D>(Index(a) * D));
}

}  // namespace ipm
}  // namespace fcsolve
