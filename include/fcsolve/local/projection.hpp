// Local solver (a): one projection step on the cone, the cheapest one-contact
// update (closed form, no iteration):
//
//   r <- P_K( r - rho (u + g(u)) ),   u = W r + q,
//
// the fixed-point map of the natural-map formulation (Acary, Bremond & Huber
// 2018, sec. 4.1; De Saxce & Feng 1998) with rho = rho_scale / lambda_max of
// the symmetric part of the diagonal block W, cached by prepare(). A fixed
// point of this map solves the one-contact problem for any rho > 0, so NSGS
// with this local solver converges to FC/II solutions even though a single
// step does not solve the local problem exactly. For the frictionless cone
// the step with rho = 1 / W is the exact solution max(0, -q / W).
#pragma once

#include <fcsolve/local/one_contact.hpp>

namespace fcsolve {
namespace local {

template <class Cone_>
struct Projection {
  FCSOLVE_ONE_CONTACT_POLICY(Cone_, "projection");

  struct Settings {
    double rho_scale = 1.0;  ///< rho = rho_scale / lambda_max(sym W^aa)
  };
  struct Data {
    Mat W;
    double mu = 0;
    double rho = 1;
  };

  static Data prepare(const Mat& W, double mu, const Settings& s) {
    Data d;
    d.W = W;
    d.mu = mu;
    d.rho = s.rho_scale * OneContact<Cone>::default_rho(W);
    return d;
  }

  static LocalResult solve(const Data& d, const Vec& q, Vec& r, const Settings&) {
    const Vec u = OneContact<Cone>::velocity(d.W, q, r);
    r = Cone::project(Vec(r - d.rho * Cone::modified_velocity(u, d.mu)), d.mu);
    LocalResult res;
    res.iterations = 1;
    res.converged = true;  // one step is all this solver does
    return res;
  }
};

}  // namespace local
}  // namespace fcsolve
