// Catalogue entry of the ADMM family: admm (FC/II; FC/I through the
// registry's reduction).
#pragma once

#include <fcsolve/admm.hpp>
#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/solvers/dispatch.hpp>
#include <fcsolve/solvers/registry.hpp>

#include <vector>

namespace fcsolve {
namespace registry {

namespace detail {

template <class Solver>
SolveOutcome solve_admm(const LocalProblemView& p, const SolveRequest& req) {
  static_assert(satisfies_solver_contract_v<Solver, LocalProblemView>);
  typename Solver::Settings s;
  static_cast<SolverSettings&>(s) = req.common;
  const SettingValues& v = req.settings;
  s.rho_init = v.enumerated<AdmmRhoInit>("rho_init");
  s.rho_strategy = v.enumerated<AdmmRhoStrategy>("rho_strategy");
  s.rho = v.real("rho");
  s.relaxation = v.real("relaxation");
  s.acceleration = v.boolean("acceleration");
  s.adapt_interval = int(v.integer("adapt_interval"));
  s.max_refactorizations = int(v.integer("max_refactorizations"));
  Solver solver(s);
  return compute_and_solve(solver, p, req);
}

inline std::vector<SettingSpec> admm_settings() {
  const AdmmSettings d;
  return {enum_setting("rho_init", d.rho_init,
                       "rho0: given (rho) or spectral (rho sqrt(L m) (L/m)^0.2, L = lambda_max(W), m = min W_ii)"),
          enum_setting("rho_strategy", d.rho_strategy,
                       "rho updates: residual balancing (x2, /2), OSQP's sqrt(r_p/r_d), or constant"),
          real_setting("rho", d.rho, "rho0 (rho_init = given) or a factor on the spectral rho0", 1e-300),
          real_setting("relaxation", d.relaxation, "over-relaxation alpha", 1.0, 1.8),
          boolean_setting("acceleration", d.acceleration, "Nesterov extrapolation with restart"),
          integer_setting("adapt_interval", d.adapt_interval, "iterations between rho updates", 1),
          integer_setting("max_refactorizations", d.max_refactorizations,
                          "cap on refactorisations of W + rho I (rho frozen beyond)", 0)};
}

}  // namespace detail

inline void add_admm_solvers(std::vector<SolverEntry>& v) {
  SolverEntry e("admm", "admm",
                "ADMM with De Saxce's shift, W + rho I factorised per rho (Acary et al. 2018)");
  e.settings = detail::admm_settings();
  e.default_max_iter = 20000;
  e.solve_local = [](const LocalProblemView& p, const SolveRequest& req) {
    return dispatch_cone_and_storage<SparseStorage>(p, [&](auto types) {
      using T = decltype(types);
      return detail::solve_admm<Admm<typename T::Cone, typename T::Storage>>(p, req);
    });
  };
  v.push_back(std::move(e));
}

}  // namespace registry
}  // namespace fcsolve
