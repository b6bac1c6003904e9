// What a time-stepping scheme puts in w and which contacts it keeps, shared by
// every scene (rigid_stepper.hpp, elastic_stepper.hpp), the examples and
// `fcsolve generate`.
//
// Moreau-Jean scheme (Jean 1999, "The non-smooth contact dynamics method",
// CMAME 177; Acary & Brogliato 2008, "Numerical Methods for Nonsmooth
// Dynamical Systems", sec. 10.1), theta in [1/2, 1]:
//   M (v+ - v) = h f_theta + H r                     (r: impulses over the step)
//   x+ = x + h (theta v+ + (1 - theta) v)
//   u  = H^T v+ + w,   K* ∋ u + g(u) ⊥ r ∈ K        (De Saxce's g(u), FC/I)
// on the index set of contacts whose gap, predicted from the free motion,
// closes within the step (Acary & Brogliato 2008, eq. 10.7, with the free
// velocity in place of v):
//   active  <=>  gap + h u_N(v_free) <= 0.
// The velocity-level Newton impact law u_N+ + e u_N >= 0 (Moreau 1988) puts
// e u_N in w_N; the drift of the gaps (the scheme works on velocities) is
// corrected as engines do, by asking a penetrating contact to separate at
// -beta gap / h (Baumgarte 1972; ODE's and Bullet's "ERP"), beyond a small
// tolerated penetration, the "slop" (Box2D's b2_linearSlop, Bullet's
// linearSlop), which keeps resting contacts from being pushed apart at every
// step:
//   w_N = e min(u_N, 0) + beta min(gap + slop, 0) / h,   w_T = 0.
#pragma once

#include <algorithm>

namespace fcsolve::scenes {

struct ContactLaw {
  double restitution = 0.0;  ///< e, Newton's coefficient
  double beta = 0.2;         ///< penetration correction per step, in [0, 1]
  double slop = 0.0;         ///< tolerated penetration (length)

  /// The index-set test: the gap closes within the step under free motion.
  static bool active(double gap, double un_free, double h) { return gap + h * un_free <= 0.0; }

  /// w_N for a contact with this gap and previous normal velocity u_N.
  double normal_offset(double gap, double un_previous, double h) const {
    return restitution * std::min(un_previous, 0.0) + beta * std::min(gap + slop, 0.0) / h;
  }
};

}  // namespace fcsolve::scenes
