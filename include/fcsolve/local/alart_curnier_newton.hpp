// Local solver (c): Alart-Curnier semismooth Newton on one contact, with the
// Goldstein-Price (default) or Armijo line search
// (settings.search.line_search). The Alart-Curnier function and its
// Jacobian are the Newton family's (formulation/alart_curnier.hpp).
#pragma once

#include <fcsolve/formulation/alart_curnier.hpp>
#include <fcsolve/local/semismooth_newton.hpp>

namespace fcsolve {
namespace local {

template <class Cone>
using AlartCurnierNewton = SemismoothNewton<Cone, AlartCurnierFunction<Cone>>;

}  // namespace local
}  // namespace fcsolve
