// Catalogue entries of the VI projection family: vi-fp, vi-eg.
#pragma once

#include <fcsolve/solvers/registry.hpp>
#include <fcsolve/vi.hpp>

namespace fcsolve {
namespace registry {

namespace detail {

template <class Cone, class Storage>
SolveOutcome solve_projected(const LocalProblemView& p, const SolveRequest& req,
                             ProjectionVariant variant) {
  ProjectedFixedPointSettings s;
  static_cast<SolverSettings&>(s) = req.common;
  s.variant = variant;
  s.rho = req.settings.real("rho");
  s.ratio_max = req.settings.real("ratio_max");
  s.ratio_min = req.settings.real("ratio_min");
  ProjectedFixedPoint<Cone, Storage> solver(s);
  solver.compute(p);
  SolveOutcome out;
  out.r = initial_reactions(req, p.size());
  out.u.resize(p.size());
  out.info = solver.solve(out.r, out.u);
  return out;
}

inline LocalSolveFunction projected_solver(ProjectionVariant variant) {
  return [variant](const LocalProblemView& p, const SolveRequest& req) {
    return dispatch_cone(p.d, [&](auto cone) {
      using Cone = decltype(cone);
      if (p.num_contacts() <= kDenseStorageMaxContacts)
        return solve_projected<Cone, DenseStorage<Cone::dim>>(p, req, variant);
      return solve_projected<Cone, SparseStorage<Cone::dim>>(p, req, variant);
    });
  };
}

inline std::vector<SettingSpec> projected_settings() {
  return {real_setting("rho", 0.0, "initial step (0: 1 / ||W||_1)", 0.0),
          real_setting("ratio_max", 0.9, "shrink rho while rho ||F(r)-F(rb)|| > ratio_max ||r-rb||", 1e-6, 1.0),
          real_setting("ratio_min", 0.3, "grow rho when the ratio falls below this", 0.0, 1.0)};
}

}  // namespace detail

inline void add_vi_solvers(std::vector<SolverEntry>& v) {
  v.push_back({"vi-fp", "vi", "projected fixed point on the VI, self-adaptive step (FP-VI-UPK)",
               detail::projected_settings(), false, 20000,
               detail::projected_solver(ProjectionVariant::FixedPoint), {}});
  v.push_back({"vi-eg", "vi", "extragradient on the VI, self-adaptive step (EG-VI-UPK)",
               detail::projected_settings(), false, 20000,
               detail::projected_solver(ProjectionVariant::ExtraGradient), {}});
}

}  // namespace registry
}  // namespace fcsolve
