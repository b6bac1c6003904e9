// Line searches on the merit psi(t) = 1/2 ||G(z + t d)||^2 along a Newton
// direction d (J d = -G, so psi'(0) = -2 psi(0)); see e.g. Nocedal & Wright,
// Numerical Optimization, 2006, sec. 3.1 (Armijo) and 3.4 (Goldstein).
//   Armijo:          psi(t) <= (1 - 2 sigma t) psi(0), t = 1, 1/2, 1/4, ...
//   Goldstein-Price: also psi(t) >= (1 - 2 (1 - sigma) t) psi(0) when t < 1,
//                    by bisection of the bracket [too short, too long].
// A non-finite psi(t) counts as "too long".
#pragma once

#include <fcsolve/newton/newton_settings.hpp>

#include <cmath>
#include <limits>

namespace fcsolve {

struct LineSearchResult {
  bool accepted = false;
  double step = 0;  ///< t
  double merit = 0;  ///< psi(t)
  int trials = 0;
};

/// `merit(t)` returns psi(t); it is called at most settings.max_line_search times.
template <class Merit>
LineSearchResult line_search(const NewtonSettings& s, double psi0, Merit&& merit) {
  LineSearchResult out;
  double t = 1, lo = 0, hi = std::numeric_limits<double>::infinity();
  for (int k = 0; k < std::max(1, s.max_line_search); ++k) {
    const double psi = merit(t);
    out.trials = k + 1;
    if (s.line_search == LineSearch::None) {
      out = {std::isfinite(psi), t, psi, 1};
      return out;
    }
    const bool armijo = std::isfinite(psi) && psi <= (1 - 2 * s.sigma * t) * psi0;
    if (!armijo) {
      hi = t;
    } else if (s.line_search == LineSearch::GoldsteinPrice && t < 1 &&
               psi < (1 - 2 * (1 - s.sigma) * t) * psi0) {
      lo = t;  // the decrease is too large for so short a step: lengthen,
      if (!out.accepted || psi < out.merit) out = {true, t, psi, k + 1};  // but keep it
    } else {
      out.accepted = true;
      out.step = t;
      out.merit = psi;
      return out;
    }
    t = std::isfinite(hi) ? 0.5 * (lo + hi) : std::min(1.0, 2 * t);
    if (t < s.min_step) break;
  }
  return out;  // accepted only if some trial met the Armijo condition
}

}  // namespace fcsolve
