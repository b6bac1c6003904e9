// Local solver (g): a few Alart-Curnier Newton steps with backtracking on
// ||G||, and one projection step when they make no progress: the cheap
// local solver of the hybrid Newton's Gauss-Seidel fallback
// (newton/newton_solver.hpp), which only has to bring the global Newton back
// to where it converges (Alart & Curnier 1991; Acary, Bremond & Huber 2018,
// sec. 4.3, [NSGS-AC]).
//
// Unlike local::AlartCurnierNewton (semismooth_newton.hpp) it has no
// closed-form take-off/stick test, no local stopping test and no
// nonmonotone full steps: Newton steps J d = -G (J = A W + B) with the
// backtracking test ||G(r + t d)|| < (1 - sigma t) ||G(r)||, t = 1, 1/2, ...
// down to min_step, until a step fails. If ||G|| did not drop, the
// projection r <- P_K(r0 - rho_N (u + g(u))) from the warm start r0.
// rho is the split spectral one of the global Newton (newton/rho_strategy.hpp).
#pragma once

#include <fcsolve/formulation/alart_curnier.hpp>
#include <fcsolve/local/one_contact.hpp>
#include <fcsolve/newton/rho_strategy.hpp>

#include <Eigen/LU>

#include <algorithm>

namespace fcsolve {
namespace local {

template <class Cone_>
struct AlartCurnierBacktracking {
  FCSOLVE_ONE_CONTACT_POLICY(Cone_, "alart-curnier-backtracking");
  using Function = AlartCurnierFunction<Cone>;

  struct Settings {
    int max_iter = 10;       ///< Newton steps
    double sigma = 1e-4;     ///< sufficient decrease of ||G||
    double min_step = 1e-3;  ///< the backtracking stops below this step length
    double tol = 1e-14;      ///< reported convergence only: ||G|| <= tol max(||r||, rho_N ||q||)
  };
  struct Data {
    Mat W;
    Vec rho;
    double mu = 0;
  };

  static Data prepare(const Mat& W, double mu, const Settings&) {
    return Data{W, contact_rho<dim>(RhoStrategy::SplitSpectralNorm, 1.0, W), mu};
  }

  static LocalResult solve(const Data& d, const Vec& q, Vec& r, const Settings& s) {
    LocalResult res;
    Vec G;
    Mat A, B;
    const Vec r0 = r;
    Function::value_and_jacobian(r, velocity(d, q, r), d.mu, d.rho, G, A, B);
    const double g0 = G.norm();
    double g = g0;
    for (; res.iterations < s.max_iter && g > 0; ++res.iterations) {
      const Vec dr = -Mat(A * d.W + B).fullPivLu().solve(G);
      if (!dr.allFinite() || !backtrack(d, q, s, dr, r, g)) break;
      Function::value_and_jacobian(r, velocity(d, q, r), d.mu, d.rho, G, A, B);
      g = G.norm();
    }
    if (g0 != 0 && !(g < g0)) {  // no local progress (or NaN): one projection step
      r = Cone::project(Vec(r0 - d.rho[0] * Cone::modified_velocity(velocity(d, q, r0), d.mu)), d.mu);
      g = Function::value(r, velocity(d, q, r), d.mu, d.rho).norm();
    }
    res.converged = g <= s.tol * std::max({r.norm(), d.rho[0] * q.norm(), 1e-300});
    return res;
  }

 private:
  static Vec velocity(const Data& d, const Vec& q, const Vec& r) { return d.W * r + q; }

  /// r <- r + t dr for the first t = 1, 1/2, ... >= min_step with
  /// ||G(r + t dr)|| < (1 - sigma t) g; false (r unchanged) if none.
  static bool backtrack(const Data& d, const Vec& q, const Settings& s, const Vec& dr, Vec& r,
                        double g) {
    for (double t = 1; t > s.min_step; t *= 0.5) {
      const Vec rt = r + t * dr;
      if (Function::value(rt, velocity(d, q, rt), d.mu, d.rho).norm() < (1 - s.sigma * t) * g) {
        r = rt;
        return true;
      }
    }
    return false;
  }
};

}  // namespace local
}  // namespace fcsolve
