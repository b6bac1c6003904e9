// The Jean-Moreau function of one contact [NSN-JM] (Jean & Moreau 1987;
// Acary, Bremond & Huber 2018, "Jean-Moreau formulation"): the Alart-Curnier
// function (alart_curnier.hpp) with the disk radius mu (r_N)_+ instead of
// mu (r_N - rho_N u_N)_+:
//   G_N = r_N - P_{R+}(r_N - rho_N u_N)
//   G_T = r_T - P_{D(mu (r_N)_+)}(r_T - rho_T u_T)
// so the tangential rows depend on r_N only (A_TN = 0, B_TN = -mu [r_N > 0] p_R).
#pragma once

#include <fcsolve/formulation/alart_curnier.hpp>

namespace fcsolve {

/// The Jean-Moreau function and its Jacobian element, one contact
/// (interface: one_contact_function.hpp).
template <class Cone>
struct JeanMoreauFunction : detail::AugmentedLagrangianFunction<Cone, false> {
  static constexpr const char* name = "jean-moreau";
};

}  // namespace fcsolve
