// What one time step of a scene did, and the settings shared by the
// steppers (rigid_stepper.hpp, elastic_stepper.hpp).
#pragma once

#include <fcsolve/core/solver_settings.hpp>
#include <fcsolve/scenes/contact_law.hpp>

namespace fcsolve::scenes {

struct StepSettings {
  double h = 2e-3;      ///< time step (s)
  double theta = 0.5;   ///< theta-method parameter in [1/2, 1]
  double gravity = 9.81;
  double mu = 0.5;      ///< friction coefficient of every contact
  ContactLaw law;       ///< what goes into w_N
  bool warm_start = true;
  double tol = 1e-8;    ///< the step solver's tolerance
  int max_iter = 10000;
};

struct StepReport {
  long step = 0;
  long contacts = 0;
  SolverInfo info;      ///< the step solver's (status NotRun without contact)
  double seconds = 0;   ///< compute() + solve()
  bool converged() const { return contacts == 0 || info.converged(); }
};

}  // namespace fcsolve::scenes
