// The Alart-Curnier function of one contact [NSN-AC] (Alart & Curnier 1991,
// the mixed "augmented Lagrangian" formulation; Acary, Bremond & Huber 2018,
// [NSN-AC]; full citations in docs/references.md),
// with rho = (rho_N, rho_T, rho_T) > 0 per component:
//   G_N = r_N - P_{R+}(r_N - rho_N u_N)
//   G_T = r_T - P_{D(mu (r_N - rho_N u_N)_+)}(r_T - rho_T u_T)
// G(r, u) = 0 exactly when (r, u) satisfies Coulomb's law at this contact,
// for any rho > 0. The Jacobian element (derived by hand from
// project_on_disk) uses x_N = r_N - rho_N u_N, x_T = r_T - rho_T u_T:
//   normal:  x_N > 0 (contact):  G_N = rho_N u_N     -> A_NN = rho_N
//            x_N <= 0 (take-off): G_N = r_N          -> B_NN = 1
//   tangent: G_T = r_T - p, p = P_{D(R)}(x_T), dp = P_x dx_T + p_R dR,
//            R = mu (x_N)_+, dR = mu [x_N > 0] (dr_N - rho_N du_N):
//            B_TT = I - P_x, A_TT = P_x diag(rho_T),
//            B_TN = -mu [x_N > 0] p_R, A_TN = mu [x_N > 0] rho_N p_R.
// The Jean-Moreau variant (jean_moreau.hpp) only changes R to mu (r_N)_+.
#pragma once

#include <fcsolve/formulation/one_contact_function.hpp>
#include <fcsolve/formulation/projection_jacobians.hpp>

#include <algorithm>

namespace fcsolve {
namespace detail {

/// The Alart-Curnier (RadiusFromAugmented = true) or Jean-Moreau (false)
/// function; the named structs below derive from it.
template <class Cone_, bool RadiusFromAugmented>
struct AugmentedLagrangianFunction
    : OneContactFunction<AugmentedLagrangianFunction<Cone_, RadiusFromAugmented>, Cone_> {
  FCSOLVE_CONE_TYPES(Cone_);

  static void evaluate(const Vec& r, const Vec& u, double mu, const Vec& rho, Vec& G, Mat* A,
                       Mat* B) {
    constexpr int D = Cone::dim;
    const double xn = r[0] - rho[0] * u[0];
    const bool contact = xn > 0;
    G[0] = contact ? rho[0] * u[0] : r[0];  // r_N - max(x_N, 0), without cancellation
    if (A) {
      A->setZero();
      B->setZero();
      if (contact) (*A)(0, 0) = rho[0];
      else (*B)(0, 0) = 1;
    }
    if constexpr (D >= 2) {
      constexpr int T = D - 1;
      const double base = RadiusFromAugmented ? xn : r[0];
      const bool radius_active = base > 0;
      const double R = radius_active ? mu * base : 0.0;
      const SmallVector<T> rho_t = rho.template tail<T>();
      const SmallVector<T> xt = r.template tail<T>() - rho_t.cwiseProduct(u.template tail<T>());
      SmallVector<T> p, p_R;
      SmallMatrix<T> P_x;
      project_on_disk<T>(xt, R, p, P_x, p_R);
      G.template tail<T>() = r.template tail<T>() - p;
      if (A) {
        B->template block<T, T>(1, 1) = SmallMatrix<T>::Identity() - P_x;
        A->template block<T, T>(1, 1) = P_x * rho_t.asDiagonal();
        if (radius_active) {
          B->template block<T, 1>(1, 0) = -mu * p_R;
          if (RadiusFromAugmented) A->template block<T, 1>(1, 0) = (mu * rho[0]) * p_R;
        }
      }
    }
  }
};

}  // namespace detail

/// The Alart-Curnier function and its Jacobian element, one contact
/// (interface: one_contact_function.hpp).
template <class Cone>
struct AlartCurnierFunction : detail::AugmentedLagrangianFunction<Cone, true> {
  static constexpr const char* name = "alart-curnier";
};

}  // namespace fcsolve
