// What the reduced (newton_solver.hpp) and the global (global_newton.hpp)
// semismooth Newton solvers share on top of NewtonLoop: the one-contact
// function and its contact residual G(r, u) with the merit psi = 1/2 ||G||^2,
// the iterate (r, u = velocity of r), the hooks of the loop that touch only
// G, and the globalised step r <- r + t dr with t from the line search.
// Derived provides update_velocity() (u from the current iterate) and the
// other hooks of NewtonLoop (newton_loop.hpp).
#pragma once

#include <fcsolve/cone/cones.hpp>
#include <fcsolve/formulation/one_contact_function.hpp>
#include <fcsolve/newton/contact_residual.hpp>
#include <fcsolve/newton/newton_loop.hpp>

namespace fcsolve {

template <class Derived, template <class> class Formulation, class ConeType>
class ContactNewton : public NewtonLoop<Derived> {
  friend NewtonLoop<Derived>;

 public:
  using Cone = ConeType;
  static constexpr int d = Cone::dim;
  using Function = Formulation<Cone>;
  using Settings = NewtonSettings;
  static_assert(is_cone_v<Cone>, "Cone must be a cone policy (cone/cones.hpp)");
  static_assert(is_one_contact_function_v<Function>, "Formulation<Cone> must be a one-contact function");

  ContactNewton(const ContactNewton&) = delete;  // a solver's system points into its Jacobian
  ContactNewton& operator=(const ContactNewton&) = delete;

 protected:
  explicit ContactNewton(const Settings& s) : NewtonLoop<Derived>(s) {}

  // ---- hooks of NewtonLoop that touch only G
  void refresh() { psi_ = residual_.evaluate(r_, u_, true); }
  void set_rho_factor(double kappa) { residual_.set_rho_factor(kappa); }

  /// The globalised step: t from the line search on merit(t) (NewtonLoop::
  /// step_length), then move(t) advances the unknowns and u, G and psi
  /// follow. False when no step could be taken. Allocates nothing.
  template <class Merit, class Move>
  bool take_step(Merit&& merit, Move&& move) {
    const double t = this->step_length(psi_, merit);
    if (t <= 0) return false;
    move(t);
    static_cast<Derived&>(*this).update_velocity();
    refresh();
    return true;
  }

  ContactResidual<Function, d> residual_;
  Vector r_, u_, best_r_;
  double psi_ = 0, scale_ = 1, reference_norm_ = 1;
};

}  // namespace fcsolve
