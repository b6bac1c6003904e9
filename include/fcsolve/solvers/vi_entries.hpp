// Catalogue entries of the VI projection family: vi-fp, vi-eg (and the
// projection machinery of fp-ds, solvers/fixed_point_entries.hpp).
#pragma once

#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/solvers/dispatch.hpp>
#include <fcsolve/solvers/registry.hpp>
#include <fcsolve/storage/block_sparse.hpp>
#include <fcsolve/vi.hpp>

#include <utility>
#include <vector>

namespace fcsolve {
namespace registry {

namespace detail {

template <class Solver>
SolveOutcome solve_projected(const LocalProblemView& p, const SolveRequest& req,
                             ProjectionVariant variant) {
  static_assert(satisfies_solver_contract_v<Solver, LocalProblemView>);
  typename Solver::Settings s;
  static_cast<SolverSettings&>(s) = req.common;
  s.variant = variant;
  s.step = req.settings.enumerated<StepRule>("step");
  s.rho = req.settings.real("rho");
  s.ratio_max = req.settings.real("ratio_max");
  s.ratio_min = req.settings.real("ratio_min");
  if (variant == ProjectionVariant::ExtraGradient)
    s.second_step = req.settings.enumerated<EgSecondStep>("second_step");
  Solver solver(s);
  return compute_and_solve(solver, p, req);
}

inline LocalSolveFunction projected_solver(ProjectionVariant variant) {
  return [variant](const LocalProblemView& p, const SolveRequest& req) {
    // block rows (BSR): W r is a row-by-row product, without the scatter and
    // the zeroing of a column-major product; F is evaluated every trial step
    return dispatch_cone_and_storage<BlockSparseStorage>(p, [&](auto types) {
      using T = decltype(types);
      return solve_projected<ProjectedFixedPoint<typename T::Cone, typename T::Storage>>(p, req,
                                                                                       variant);
    });
  };
}

/// The entries' settings; `step` defaults to `step_rule` (vi-*: the
/// struct's self-adaptive rule, fp-ds: fixed).
inline std::vector<SettingSpec> projected_settings(StepRule step_rule) {
  const ProjectedFixedPointSettings d;
  return {enum_setting("step", step_rule, "step rule: self-adaptive (Khobotov) or fixed rho"),
          real_setting("rho", d.rho, "initial (fixed: the) step (0: 1 / ||W||_1)", 0.0),
          real_setting("ratio_max", d.ratio_max,
                       "shrink rho while rho ||F(r)-F(rb)|| > ratio_max ||r-rb||", 1e-6, 1.0),
          real_setting("ratio_min", d.ratio_min, "grow rho when the ratio falls below this", 0.0,
                       1.0)};
}

inline SolverEntry projected_entry(std::string name, std::string summary,
                                   ProjectionVariant variant, std::string family = "vi",
                                   StepRule step_rule = ProjectedFixedPointSettings().step) {
  SolverEntry e(std::move(name), std::move(family), std::move(summary));
  e.settings = projected_settings(step_rule);
  if (variant == ProjectionVariant::ExtraGradient)
    e.settings.push_back(enum_setting(
        "second_step", ProjectedFixedPointSettings().second_step,
        "second step: predictor, from the trial point (as Siconos' VI_EG), or korpelevich, "
        "from r"));
  e.default_max_iter = 20000;
  e.solve_local = projected_solver(variant);
  return e;
}

}  // namespace detail

inline void add_vi_solvers(std::vector<SolverEntry>& v) {
  v.push_back(detail::projected_entry(
      "vi-fp", "projected fixed point on the VI, self-adaptive step (FP-VI-UPK)",
      ProjectionVariant::FixedPoint));
  v.push_back(detail::projected_entry(
      "vi-eg", "extragradient on the VI, self-adaptive step (EG-VI-UPK; second step from the trial point by default)",
      ProjectionVariant::ExtraGradient));
}

}  // namespace registry
}  // namespace fcsolve
