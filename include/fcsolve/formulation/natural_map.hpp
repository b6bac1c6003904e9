// The natural map of one contact [NSN-NM] (Acary, Bremond & Huber 2018,
// "direct normal map reformulation"; the error measure of problem/error.hpp is
// its value at rho = 1):
//   G = r - P_K(r - rho (u + g(u))),   g(u) = (mu ||u_T||, 0)   (De Saxce 1992)
// The solution set is that of the VI "find r in K, <u~, s - r> >= 0 for all
// s in K" only for a scalar rho (a diagonal scaling would change the cone
// the VI lives in), so this function uses rho_N = rho[0] for every component.
// With z = r - rho (u + g(u)) and J = dP_K(z) (projection_jacobians.hpp):
//   dG = (I - J) dr + rho J (I + Dg(u)) du,  i.e. B = I - J, A = rho J (I + Dg).
#pragma once

#include <fcsolve/formulation/one_contact_function.hpp>
#include <fcsolve/formulation/projection_jacobians.hpp>

namespace fcsolve {

/// The natural-map function and its Jacobian element, one contact
/// (interface: one_contact_function.hpp).
template <class Cone_>
struct NaturalMapFunction : OneContactFunction<NaturalMapFunction<Cone_>, Cone_> {
  FCSOLVE_ONE_CONTACT_POLICY(Cone_, "natural-map");

  static void evaluate(const Vec& r, const Vec& u, double mu, const Vec& rho, Vec& G, Mat* A,
                       Mat* B) {
    const Vec z = r - rho[0] * Cone::modified_velocity(u, mu);
    G = r - Cone::project(z, mu);
    if (!A) return;
    Mat J;
    if constexpr (dim == 1) J(0, 0) = z[0] > 0 ? 1.0 : 0.0;
    else J = coulomb_projection_jacobian<dim>(z, mu);
    *B = Mat::Identity() - J;
    A->noalias() = rho[0] * J * modified_velocity_jacobian<dim>(u, mu);
  }
};

}  // namespace fcsolve
