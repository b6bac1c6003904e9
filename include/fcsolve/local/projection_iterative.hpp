// Local solver (b): projections iterated to local convergence, with a step
// per component and an optional proximal regularisation, for diagonal
// blocks W^aa that one projection on the cone (local/projection.hpp) treats
// badly: a normal stiffness far from the tangential one, strong N-T coupling.
//
// One iteration is a Gauss-Seidel pass over the normal and the tangential
// parts of the Jean-Moreau formulation (Jean & Moreau 1987; Acary, Bremond &
// Huber 2018, eq. (NSN-JM)):
//   r_N <- P_{R+}( r_N - rho_N (u_N + sigma (r_N - r0_N)) ),
//   r_T <- P_{D(mu r_N)}( r_T - rho_T (u_T + sigma (r_T - r0_T)) ),
// u = W r + q recomputed after each part, D(R) the disk of radius R,
// rho_N = 1 / (W_NN + sigma) (the exact normal solve for fixed r_T) and
// rho_T = 1 / (lambda_max(sym W_TT) + sigma) (a safe projected-gradient step).
// Its fixed points are exactly the one-contact solutions: the normal map is
// Signorini's condition, the tangential one Coulomb's law on the disk of
// radius mu r_N. Splitting N and T is what allows two step sizes; a
// projection on the cone has one.
// sigma = regularization * lambda_max(sym W) adds the proximal term of the
// proximal point method (Rockafellar 1976) centred on the warm start r0: it
// makes a singular or ill-conditioned block strongly monotone, and it does
// not move the fixed points of the NSGS sweep (r = r0 there).
// Take-off (q_N >= 0) and stick (-W^-1 q ∈ K) are tested first, in closed
// form (without regularisation only: sigma > 0 asks for the proximal step).
// The pass is averaged with the previous iterate (Krasnoselskii-Mann, weight
// halved whenever the residual grows): plain iteration can cycle when mu
// times the N-T coupling is large.
// Stops when the natural-map residual ||r - P_K(r - u - g(u))|| <= tol ||q||,
// or (sigma > 0) when the iterates stop moving.
#pragma once

#include <fcsolve/local/one_contact.hpp>

#include <algorithm>
#include <cmath>

namespace fcsolve {
namespace local {

template <class Cone_>
struct ProjectionIterative {
  FCSOLVE_ONE_CONTACT_POLICY(Cone_, "projection-iterative");

  struct Settings {
    double tol = 1e-12;         ///< local natural-map residual / ||q||
    int max_iter = 200;         ///< local iterations
    double regularization = 0;  ///< sigma / lambda_max(sym W^aa)
  };
  struct Data {
    Mat W, W_inv;            ///< W_inv: zero when W is singular
    double mu = 0;
    double rho_n = 0, rho_t = 0;  ///< steps of the normal and tangential projections
    double sigma = 0;             ///< proximal weight
  };

  static Data prepare(const Mat& W, double mu, const Settings& s) {
    Data d;
    d.W = W;
    d.mu = mu;
    d.W_inv = OneContact<Cone>::inverse_or_zero(W);
    d.sigma = s.regularization * std::max(OneContact<Cone>::largest_eigenvalue(W), 0.0);
    const double wn = W(0, 0) + d.sigma;
    d.rho_n = wn > 0 ? 1 / wn : 0;  // a zero block cannot move r
    if constexpr (dim > 1) {
      const SmallMatrix<dim - 1> Wt = W.template bottomRightCorner<dim - 1, dim - 1>();
      const SmallMatrix<dim - 1> S = 0.5 * (Wt + Wt.transpose());
      double lt = S(0, 0);
      if constexpr (dim == 3) {  // largest eigenvalue of a symmetric 2 x 2
        const double mean = 0.5 * (S(0, 0) + S(1, 1)), half = 0.5 * (S(0, 0) - S(1, 1));
        lt = mean + std::sqrt(half * half + S(0, 1) * S(0, 1));
      }
      lt += d.sigma;
      d.rho_t = lt > 0 ? 1 / lt : 0;
    }
    return d;
  }

  static LocalResult solve(const Data& d, const Vec& q, Vec& r, const Settings& s) {
    LocalResult res;
    if (OneContact<Cone>::takes_off(q)) {  // exact, and what the iteration would reach
      r.setZero();
      res.converged = true;
      res.kind = ContactCase::TakeOff;
      return res;
    }
    const Vec stick = -d.W_inv * q;  // exact when it lies in K (zero if W is singular)
    if (d.sigma == 0 && Cone::contains(stick, d.mu) && stick.squaredNorm() > 0) {
      r = stick;
      res.converged = true;
      res.kind = ContactCase::Stick;
      return res;
    }
    const Vec r0 = r;
    const double scale = std::max(q.norm(), 1e-300);
    double residual = OneContact<Cone>::residual(d.W, q, d.mu, r);
    double relax = 1;  // Krasnoselskii-Mann averaging, halved when the residual grows
    for (res.iterations = 1; res.iterations <= s.max_iter; ++res.iterations) {
      const Vec r_prev = r;
      const double un = d.W.row(0).dot(r) + q[0];
      r[0] = std::max(0.0, r[0] - d.rho_n * (un + d.sigma * (r[0] - r0[0])));
      if constexpr (dim > 1) {
        constexpr int t = dim - 1;
        const SmallVector<t> ut = d.W.template bottomRows<t>() * r + q.template tail<t>();
        SmallVector<t> rt = r.template tail<t>() -
                            d.rho_t * (ut + d.sigma * (r.template tail<t>() - r0.template tail<t>()));
        const double radius = d.mu * r[0], norm = rt.norm();
        if (norm > radius) rt *= norm > 0 ? radius / norm : 0.0;
        r.template tail<t>() = rt;
      }
      if (relax < 1) r = r_prev + relax * (r - r_prev);  // stays in K (convex)
      const double next = OneContact<Cone>::residual(d.W, q, d.mu, r);
      if (next <= s.tol * scale ||
          (d.sigma > 0 && (r - r_prev).norm() <= s.tol * std::max(r.norm(), 1e-300))) {
        res.converged = true;
        break;
      }
      if (next > residual && relax > 1.0 / 64) relax *= 0.5;
      residual = next;
    }
    res.iterations = std::min(res.iterations, s.max_iter);
    return res;
  }
};

}  // namespace local
}  // namespace fcsolve
