// The step settings (fcsolve/scenes/step_report.hpp) from an example's
// parameters: both examples name them alike.
#pragma once

#include <fcsolve/scenes/step_report.hpp>

namespace stepping {

template <class Parameters>
fcsolve::scenes::StepSettings step_settings(const Parameters& p) {
  fcsolve::scenes::StepSettings s;
  s.h = p.h;
  s.theta = p.theta;
  s.mu = p.mu;
  s.law = p.law;
  s.warm_start = p.warm_start;
  s.tol = p.tol;
  s.max_iter = int(p.max_iter);
  return s;
}

}  // namespace stepping
