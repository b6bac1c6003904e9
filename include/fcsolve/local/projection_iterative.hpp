// Local solver (b): projection iterated to local convergence, with a
// self-adaptive step and an optional proximal regularisation, for diagonal
// blocks W^aa whose conditioning makes one projection step (local/projection.hpp)
// a poor local solve.
//
// Extragradient iteration on the one-contact VI  -F(r) ∈ N_K(r),
//   F(r) = u + g(u) + sigma (r - r0),  u = W r + q,
//   rbar = P_K(r - rho F(r)),   r <- P_K(r - rho F(rbar))
// (Korpelevich 1976), with rho adapted by the Armijo-like rule of Khobotov
// (1987) used in Acary, Bremond & Huber 2018, sec. 4.1 [EG-VI]:
//   shrink rho (rho <- tau rho) until rho ||F(r) - F(rbar)|| <= L ||r - rbar||,
//   grow it (rho <- rho / tau) when the test holds with L_min instead of L.
// sigma = regularization * lambda_max(W^aa) adds the proximal term of the
// proximal point method (Rockafellar 1976) centred on the warm start r0: it
// makes an ill-conditioned or singular block strongly monotone, and it does
// not move the fixed points of the NSGS sweep (r = r0 there).
// Stops when ||r - P_K(r - F(r))|| <= tol * max(||q||, tiny).
#pragma once

#include <fcsolve/local/one_contact.hpp>

#include <algorithm>

namespace fcsolve {
namespace local {

template <class Cone_>
struct ProjectionIterative {
  using Cone = Cone_;
  using Vec = typename Cone::Vec;
  using Mat = SmallMatrix<Cone::dim>;
  static constexpr const char* name = "projection-iterative";

  struct Settings {
    double tol = 1e-12;          ///< local natural-map residual / ||q||
    int max_iter = 100;          ///< local iterations
    double regularization = 0;   ///< sigma / lambda_max(sym W^aa)
    double L = 0.9;              ///< step acceptance (Khobotov)
    double L_min = 0.3;          ///< step growth threshold
    double tau = 2.0 / 3.0;      ///< step shrink factor
  };
  struct Data {
    Mat W;
    double mu = 0;
    double rho = 1;     ///< initial step 1 / (lambda_max + sigma)
    double sigma = 0;   ///< proximal weight
  };

  static Data prepare(const Mat& W, double mu, const Settings& s) {
    Data d;
    d.W = W;
    d.mu = mu;
    const double lmax = std::max(OneContact<Cone>::largest_eigenvalue(W), 0.0);
    d.sigma = s.regularization * lmax;
    d.rho = lmax + d.sigma > 0 ? 1.0 / (lmax + d.sigma) : 1.0;
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
    const Vec r0 = r;
    const auto F = [&](const Vec& x) -> Vec {
      const Vec u = OneContact<Cone>::velocity(d.W, q, x);
      return Cone::modified_velocity(u, d.mu) + d.sigma * (x - r0);
    };
    const double scale = std::max(q.norm(), 1e-300);
    double rho = d.rho;
    for (res.iterations = 0; res.iterations < s.max_iter; ++res.iterations) {
      const Vec Fr = F(r);
      if ((r - Cone::project(Vec(r - Fr), d.mu)).norm() <= s.tol * scale) {
        res.converged = true;
        break;
      }
      Vec rbar, Fbar;
      double ratio = 0;  // rho ||F(r) - F(rbar)|| / ||r - rbar||
      for (int shrink = 0; shrink < 60; ++shrink) {
        rbar = Cone::project(Vec(r - rho * Fr), d.mu);
        Fbar = F(rbar);
        const double step = (r - rbar).norm();
        ratio = step > 0 ? rho * (Fr - Fbar).norm() / step : 0;
        if (ratio <= s.L) break;
        rho *= s.tau;
      }
      r = Cone::project(Vec(r - rho * Fbar), d.mu);
      if (ratio < s.L_min) rho /= s.tau;
    }
    return res;
  }
};

}  // namespace local
}  // namespace fcsolve
