// Catalogue entries of the fixed points (fixed_point.hpp):
//   fp-ds   De Saxce's fixed point (ProjectedFixedPoint, fixed rho by default;
//           step=self-adaptive is vi-fp's rule)
//   tresca  Tresca fixed point, inner NSGS on the cylinder
//   pana    Panagiotopoulos' normal / tangential alternation, inner NSGS
// Small scenes (<= kDenseStorageMaxContacts contacts) store W dense; the
// others as the NSGS entries do (block rows).
#pragma once

#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/fixed_point.hpp>
#include <fcsolve/solvers/dispatch.hpp>
#include <fcsolve/solvers/registry.hpp>
#include <fcsolve/solvers/vi_entries.hpp>

#include <string>
#include <utility>
#include <vector>

namespace fcsolve {
namespace registry {
namespace fixed_point_detail {

inline std::vector<SettingSpec> splitting_specs() {
  const SplittingSettings d;
  return {real_setting("inner_tol_ratio", d.inner_tol_ratio,
                       "inner tolerance max(inner_tol_ratio * err, tol)", 0.0, 1.0),
          integer_setting("inner_max_iter", d.inner_max_iter, "sweeps of each inner NSGS", 1, 1e9)};
}

/// The splitting Method<Cone, Storage> on p.
template <template <class, class> class Method>
LocalSolveFunction splitting_solver() {
  return [](const LocalProblemView& p, const SolveRequest& req) {
    return dispatch_cone_and_storage<BlockSparseStorage>(p, [&](auto types) {
      using T = decltype(types);
      using Solver = Method<typename T::Cone, typename T::Storage>;
      static_assert(satisfies_solver_contract_v<Solver, LocalProblemView>);
      Solver solver;
      auto& s = solver.settings();
      static_cast<SolverSettings&>(s) = req.common;
      s.inner_tol_ratio = req.settings.real("inner_tol_ratio");
      s.inner_max_iter = int(req.settings.integer("inner_max_iter"));
      return compute_and_solve(solver, p, req);
    });
  };
}

inline SolverEntry splitting_entry(std::string name, std::string summary, LocalSolveFunction solve) {
  SolverEntry e(std::move(name), "fixed-point", std::move(summary));
  e.settings = splitting_specs();
  e.default_max_iter = SplittingSettings().max_iter;
  e.solve_local = std::move(solve);
  return e;
}

}  // namespace fixed_point_detail

inline void add_fixed_point_solvers(std::vector<SolverEntry>& v) {
  using namespace fixed_point_detail;
  v.push_back(detail::projected_entry("fp-ds", "De Saxce's fixed point r <- P_K(r - rho (u + g(u))) (DSFP)",
                                      ProjectionVariant::FixedPoint, "fixed-point", StepRule::Fixed));
  v.push_back(splitting_entry("tresca",
                              "Tresca fixed point: threshold s = mu r_N, inner NSGS on the cylinder (TFP)",
                              splitting_solver<TrescaFixedPoint>()));
  v.push_back(splitting_entry(
      "pana", "Panagiotopoulos: normal LCP and tangential disc problems in turn, inner NSGS (PFP)",
      splitting_solver<Panagiotopoulos>()));
}

}  // namespace registry
}  // namespace fcsolve
