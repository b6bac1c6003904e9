// Local solver (f): Newton first, projection when Newton stalls (the
// "hybrid" local strategies of Acary, Bremond & Huber 2018, sec. 4.3).
//
// 1. Alart-Curnier semismooth Newton (local/alart_curnier_newton.hpp) from
//    the warm start: fast and exact when it converges.
// 2. If it stalls (line search failure or iteration cap), the iterated
//    projection (local/projection_iterative.hpp) from the better of the warm
//    start and Newton's last iterate (by the natural-map residual): slow but
//    hard to break.
// 3. Newton once more from there, to finish quickly.
// The better of the candidates is returned.
#pragma once

#include <fcsolve/local/alart_curnier_newton.hpp>
#include <fcsolve/local/projection_iterative.hpp>

namespace fcsolve {
namespace local {

template <class Cone_>
struct Hybrid {
  FCSOLVE_ONE_CONTACT_POLICY(Cone_, "hybrid");
  using NewtonSolver = AlartCurnierNewton<Cone>;
  using ProjectionSolver = ProjectionIterative<Cone>;

  struct Settings {
    typename NewtonSolver::Settings newton;
    typename ProjectionSolver::Settings projection;
  };
  struct Data {
    typename NewtonSolver::Data newton;
    typename ProjectionSolver::Data projection;
  };

  static Data prepare(const Mat& W, double mu, const Settings& s) {
    return Data{NewtonSolver::prepare(W, mu, s.newton), ProjectionSolver::prepare(W, mu, s.projection)};
  }

  static LocalResult solve(const Data& d, const Vec& q, Vec& r, const Settings& s) {
    const Vec r0 = r;
    LocalResult res = NewtonSolver::solve(d.newton, q, r, s.newton);
    if (res.converged) return res;
    const Mat& W = d.newton.W;
    const double mu = d.newton.mu;
    if (!r.allFinite() || OneContact<Cone>::residual(W, q, mu, r0) < OneContact<Cone>::residual(W, q, mu, r))
      r = r0;
    const LocalResult proj = ProjectionSolver::solve(d.projection, q, r, s.projection);
    res.iterations += proj.iterations;
    res.kind = proj.kind;
    res.converged = proj.converged;
    if (proj.converged) return res;
    const Vec r_proj = r;
    const LocalResult again = NewtonSolver::solve(d.newton, q, r, s.newton);
    res.iterations += again.iterations;
    if (again.converged) {
      res.converged = true;
      res.kind = again.kind;
    } else if (!r.allFinite() ||
               OneContact<Cone>::residual(W, q, mu, r_proj) < OneContact<Cone>::residual(W, q, mu, r)) {
      r = r_proj;
    }
    return res;
  }
};

}  // namespace local
}  // namespace fcsolve
