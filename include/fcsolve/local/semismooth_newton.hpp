// Local semismooth Newton: one contact's nonsmooth equation G(r) = 0 solved
// by Newton's method with a line search (the local solvers of NSGS-AC,
// NSGS-FB: Acary, Bremond & Huber 2018, sec. 4.3; Alart & Curnier 1991).
//
// G(r) = Function(r, u = W r + q) is one of the Newton family's one-contact
// functions (formulation/: Alart-Curnier, Jean-Moreau, natural map,
// Fischer-Burmeister), which return G and an element dG = A du + B dr of its
// generalised Jacobian; for one contact du = W dr, so
//   J = A W + B,   J d = -G,   r <- r + t d,
// with t from the Armijo or Goldstein-Price line search on psi = 1/2 ||G||^2
// (newton/line_search.hpp). rho = (rho_N, rho_T, ...) comes from the
// diagonal block (rho_N = 1 / W_NN, rho_T = 1 / ||W_TT||_2, the split
// spectral strategy, OneContact::split_rho). A singular J is shifted,
// J + delta I. Take-off (q_N >= 0) and stick (-W^-1 q ∈ K) are tested first
// in closed form: exact, and what Newton would reach anyway.
// Converged: ||G|| <= tol * max(||r||, rho_N ||q||).
#pragma once

#include <fcsolve/local/one_contact.hpp>
#include <fcsolve/newton/line_search.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fcsolve {
namespace local {

template <class Cone_, class Function>
struct SemismoothNewton {
  FCSOLVE_ONE_CONTACT_POLICY(Cone_, Function::name);

  struct Settings {
    double tol = 1e-14;     ///< ||G|| relative to max(||r||, rho_N ||q||)
    int max_iter = 20;      ///< Newton steps
    bool closed_form_first = true;  ///< take-off and stick tests before Newton
    /// Full steps allowed when the line search fails (nonmonotone Newton, as
    /// Siconos' NSN does); the best iterate is returned if Newton fails.
    int max_full_steps = 3;
    /// Line search (only line_search, sigma, max_line_search and min_step
    /// are read: newton/line_search.hpp).
    NewtonSettings search = default_search();
  };
  struct Data {
    Mat W, W_inv;  ///< W_inv: zero when W is singular
    Vec rho;
    double mu = 0;
  };

  static NewtonSettings default_search() {
    NewtonSettings s;
    s.line_search = LineSearch::GoldsteinPrice;
    s.max_line_search = 20;
    return s;
  }

  static Data prepare(const Mat& W, double mu, const Settings&) {
    Data d;
    d.W = W;
    d.W_inv = OneContact<Cone>::inverse_or_zero(W);
    d.mu = mu;
    d.rho = OneContact<Cone>::split_rho(W);
    return d;
  }

  /// G(r) = Function(r, W r + q)
  static Vec residual(const Data& d, const Vec& q, const Vec& r) {
    return Function::value(r, OneContact<Cone>::velocity(d.W, q, r), d.mu, d.rho);
  }

  static LocalResult solve(const Data& d, const Vec& q, Vec& r, const Settings& s) {
    LocalResult res;
    if (s.closed_form_first && closed_form(d, q, r, res)) return res;
    const double scale_q = d.rho[0] * q.norm();
    Vec G, best = r;
    Mat A, B;
    double best_norm = std::numeric_limits<double>::infinity();
    int full_steps = 0;
    for (res.iterations = 0; res.iterations < s.max_iter; ++res.iterations) {
      Function::value_and_jacobian(r, OneContact<Cone>::velocity(d.W, q, r), d.mu, d.rho, G, A, B);
      const double norm_g = G.norm();
      if (!std::isfinite(norm_g)) break;
      if (norm_g < best_norm) {
        best_norm = norm_g;
        best = r;
      }
      if (norm_g <= s.tol * std::max({r.norm(), scale_q, 1e-300})) {
        res.converged = true;
        break;
      }
      const Vec step = newton_direction(Mat(A * d.W + B), G);
      const double psi0 = 0.5 * norm_g * norm_g;
      const LineSearchResult ls = line_search(
          s.search, psi0,
          [&](double t) { return 0.5 * residual(d, q, Vec(r + t * step)).squaredNorm(); },
          psi0);  // monotone test (reference = psi0): few iterations, no merit history
      if (ls.accepted) {
        r += ls.step * step;
      } else if (full_steps++ < s.max_full_steps) {
        r += step;  // nonmonotone: a full step out of a kink the line search cannot leave
      } else {
        break;  // stalled: the caller (hybrid, NSGS) decides
      }
    }
    if (!res.converged) r = best;
    return res;
  }

 private:
  /// Take-off or stick, in closed form.
  static bool closed_form(const Data& d, const Vec& q, Vec& r, LocalResult& res) {
    if (OneContact<Cone>::takes_off(q)) {
      r.setZero();
      res.kind = ContactCase::TakeOff;
    } else {
      const Vec stick = -d.W_inv * q;  // zero when W is singular
      if (stick.squaredNorm() == 0 || !Cone::contains(stick, d.mu)) return false;
      r = stick;
      res.kind = ContactCase::Stick;
    }
    res.converged = true;
    return true;
  }

  /// d = -J^-1 G, with J shifted by delta I while it is singular.
  static Vec newton_direction(Mat J, const Vec& G) {
    const double shift = 1e-10 * std::max(1.0, J.diagonal().cwiseAbs().maxCoeff());
    for (double delta = shift; delta < 1e6 * shift; delta *= 100) {
      const Mat J_inv = OneContact<Cone>::inverse_or_zero(J);
      if (!J_inv.isZero(0)) return -J_inv * G;
      J.diagonal().array() += delta;
    }
    return -G;  // a steepest-descent-like fallback: the line search judges it
  }
};

}  // namespace local
}  // namespace fcsolve
