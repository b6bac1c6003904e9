// Catalogue entries of the ADMM family:
//   admm         FC/II (FC/I through the registry's reduction)
//   admm-global  FC/I natively in (v, r), M + rho H H^T factorised per rho;
//                global-only, as ppa-global (with bilateral constraints:
//                admm on the reduced form)
#pragma once

#include <fcsolve/admm.hpp>
#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/solvers/dispatch.hpp>
#include <fcsolve/solvers/registry.hpp>

#include <vector>

namespace fcsolve {
namespace registry {

namespace detail {

/// The request's settings into AdmmSettings (rho_init: admm only).
inline AdmmSettings configure(const SolveRequest& req, bool with_rho_init) {
  AdmmSettings s;
  static_cast<SolverSettings&>(s) = req.common;
  const SettingValues& v = req.settings;
  if (with_rho_init) s.rho_init = v.enumerated<AdmmRhoInit>("rho_init");
  s.rho_strategy = v.enumerated<AdmmRhoStrategy>("rho_strategy");
  s.rho = v.real("rho");
  s.relaxation = v.real("relaxation");
  s.acceleration = v.boolean("acceleration");
  s.adapt_interval = int(v.integer("adapt_interval"));
  s.max_refactorizations = int(v.integer("max_refactorizations"));
  return s;
}

/// admm: FC/II, cone and storage from the catalogue's dispatch.
inline SolveOutcome solve_admm_local(const LocalProblemView& p, const SolveRequest& req,
                                     bool with_rho_init = true) {
  return dispatch_cone_and_storage<SparseStorage>(p, [&](auto types) {
    using T = decltype(types);
    using Solver = Admm<typename T::Cone, typename T::Storage>;
    static_assert(satisfies_solver_contract_v<Solver, LocalProblemView>);
    Solver solver(configure(req, with_rho_init));
    return compute_and_solve(solver, p, req);
  });
}

/// admm-global: FC/I in (v, r); bilateral constraints go through the
/// registry's reduction to admm (AdmmGlobal does not handle G, b).
inline SolveOutcome solve_admm_global(const GlobalProblemView& p, const SolveRequest& req) {
  if (p.has_bilateral())
    return solve_bilateral_by_reduction(p, req, [](const LocalProblemView& reduced, const SolveRequest& within) {
      return solve_admm_local(reduced, within, false);
    });
  return dispatch_cone(p.d, [&](auto cone) {
    using Solver = AdmmGlobal<decltype(cone)>;
    static_assert(satisfies_solver_contract_v<Solver, GlobalProblemView>);
    Solver admm(configure(req, false));
    return compute_and_solve(admm, p, req);
  });
}

/// The settings of both entries; rho_init only for admm (the spectral rho0
/// needs W).
inline std::vector<SettingSpec> admm_settings(bool with_rho_init) {
  const AdmmSettings d;
  std::vector<SettingSpec> specs;
  if (with_rho_init)
    specs.push_back(enum_setting(
        "rho_init", d.rho_init,
        "rho0: given (rho) or spectral (rho sqrt(L m) (L/m)^0.2, L = lambda_max(W), m = min W_ii)"));
  std::vector<SettingSpec> common = {
          enum_setting("rho_strategy", d.rho_strategy,
                       "rho updates: residual balancing (x2, /2), OSQP's sqrt(r_p/r_d), or constant"),
          real_setting("rho", d.rho,
                       with_rho_init ? "rho0 (rho_init = given) or a factor on the spectral rho0"
                                     : "rho0 in units of 1 / mean diag(H^T diag(M)^-1 H)",
                       1e-300),
          real_setting("relaxation", d.relaxation, "over-relaxation alpha", 1.0, 1.8),
          boolean_setting("acceleration", d.acceleration, "Nesterov extrapolation with restart"),
          integer_setting("adapt_interval", d.adapt_interval, "iterations between rho updates", 1),
          integer_setting("max_refactorizations", d.max_refactorizations,
                          "cap on refactorisations of the rho system (rho frozen beyond)", 0)};
  specs.insert(specs.end(), common.begin(), common.end());
  return specs;
}

}  // namespace detail

inline void add_admm_solvers(std::vector<SolverEntry>& v) {
  SolverEntry e("admm", "admm",
                "ADMM with De Saxce's shift, W + rho I factorised per rho (Acary et al. 2018)");
  e.settings = detail::admm_settings(true);
  e.default_max_iter = 20000;
  e.solve_local = [](const LocalProblemView& p, const SolveRequest& req) {
    return detail::solve_admm_local(p, req);
  };
  v.push_back(std::move(e));
  SolverEntry global("admm-global", "admm",
                     "ADMM with De Saxce's shift on FC/I in (v, r), M + rho H H^T factorised per rho, "
                     "W never formed");
  global.settings = detail::admm_settings(false);
  global.default_max_iter = 20000;
  global.solve_global = detail::solve_admm_global;
  v.push_back(std::move(global));
}

}  // namespace registry
}  // namespace fcsolve
