// Catalogue entries of the semismooth Newton family (newton.hpp):
//   nsn-ac, nsn-jm, nsn-nm, nsn-fb         reduced form (FC/II; FC/I by reduction)
//   nsn-ac-hybrid                          + Gauss-Seidel fallback when Newton stalls
//   nsn-ac-global, nsn-jm-global, nsn-nm-global, nsn-fb-global
//                                          FC/I natively in (v, r), W never formed
// Small scenes (<= kDenseStorageMaxContacts contacts) use DenseStorage and a
// dense LU, the others SparseStorage and the default sparse LU (UMFPACK).
#pragma once

#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/newton.hpp>
#include <fcsolve/solvers/dispatch.hpp>
#include <fcsolve/solvers/registry.hpp>

#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace fcsolve {
namespace registry {

namespace newton_detail {

inline NewtonSettings newton_settings(const SolveRequest& req, bool hybrid) {
  NewtonSettings s;
  static_cast<SolverSettings&>(s) = req.common;
  const SettingValues& v = req.settings;
  s.line_search = v.enumerated<LineSearch>("line_search");
  s.rho_strategy = v.enumerated<RhoStrategy>("rho_strategy");
  s.line_search_memory = int(v.integer("line_search_memory"));
  s.rho = v.real("rho");
  s.levenberg_marquardt = v.real("levenberg_marquardt");
  s.nonmonotone = v.boolean("nonmonotone");
  s.stall_window = int(v.integer("stall_window"));
  s.hybrid = hybrid;
  if (hybrid) {
    s.fallback_sweeps = int(v.integer("fallback_sweeps"));
    s.resume_ratio = v.real("resume_ratio");
  }
  return s;
}

/// Runs a solver of the contract (core/solver_contract.hpp) from the
/// request's warm start; `second` is u (FC/II) or v (FC/I) of that size.
template <class Solver, class View>
SolveOutcome run(const View& p, const SolveRequest& req, bool hybrid, Vector SolveOutcome::*second,
                 Index second_size) {
  static_assert(satisfies_solver_contract_v<Solver, View>);
  Solver solver(newton_settings(req, hybrid));
  compute_within_time(solver, p);
  SolveOutcome out;
  out.r = initial_reactions(req, p.size());
  (out.*second).resize(second_size);
  out.info = solver.solve(out.r, out.*second);
  if constexpr (std::is_same_v<View, GlobalProblemView>)
    out.reduced_q_norm = solver.free_velocity_norm();  // the registry need not factorise M again
  return out;
}

template <template <class> class F>
LocalSolveFunction reduced_solver(bool hybrid) {
  return [hybrid](const LocalProblemView& p, const SolveRequest& req) {
    return dispatch_cone_and_storage<SparseStorage>(p, [&](auto types) {
      using T = decltype(types);
      using Solver = Newton<F, typename T::Cone, typename T::Storage>;
      return run<Solver>(p, req, hybrid, &SolveOutcome::u, p.size());
    });
  };
}

/// FC/I in (v, r); problems with bilateral constraints go through the
/// registry's reduction (GlobalNewton does not handle G, b).
template <template <class> class F>
GlobalSolveFunction global_solver() {
  return [](const GlobalProblemView& p, const SolveRequest& req) {
    if (p.has_bilateral())
      return solve_bilateral_by_reduction(p, req, [](const LocalProblemView& reduced, const SolveRequest& within) {
        return reduced_solver<F>(false)(reduced, within);
      });
    return dispatch_cone(p.d, [&](auto cone) {
      using Solver = GlobalNewton<F, decltype(cone)>;
      return run<Solver>(p, req, false, &SolveOutcome::v, p.num_dofs());
    });
  };
}

inline std::vector<SettingSpec> newton_settings_specs(bool hybrid) {
  const NewtonSettings d;
  // The hybrid leaves Newton sooner: its fallback, not a rho restart, is
  // what a stall triggers.
  const int stall_window = hybrid ? 20 : d.stall_window;
  std::vector<SettingSpec> v = {
      enum_setting("line_search", d.line_search, "line search on 1/2 ||G||^2"),
      integer_setting("line_search_memory", d.line_search_memory,
                      "nonmonotone Armijo test against the largest of the last N merits (1: monotone)", 1, 16),
      enum_setting("rho_strategy", d.rho_strategy,
                   "per-contact rho: rho / W_NN and rho / ||W_TT||, rho / ||W^aa||, rho, or "
                   "split-spectral rescaled when Newton stalls"),
      real_setting("rho", d.rho, "the constant rho, or the factor on the spectral values", 1e-12),
      real_setting("levenberg_marquardt", d.levenberg_marquardt,
                   "shift (J + delta I), delta = this * max|J_ii| * min(1, ||G|| / ||G(0)||); 0: plain Newton",
                   0.0),
      boolean_setting("nonmonotone", d.nonmonotone, "take the full step when the line search fails"),
      integer_setting("stall_window", stall_window,
                      "iterations without halving the best error that count as a stall (0: never)", 0),
  };
  if (hybrid) {
    v.push_back(integer_setting("fallback_sweeps", d.fallback_sweeps, "Gauss-Seidel sweeps per fallback", 1));
    v.push_back(real_setting("resume_ratio", d.resume_ratio, "resume Newton once the error dropped by this", 0.0, 1.0));
  }
  return v;
}

/// An entry of the family, its solve functions still to set.
inline SolverEntry newton_entry(std::string name, std::string summary, bool hybrid = false) {
  SolverEntry e(std::move(name), "newton", std::move(summary));
  e.settings = newton_settings_specs(hybrid);
  e.default_max_iter = hybrid ? 5000 : 1000;
  return e;
}

}  // namespace newton_detail

inline void add_newton_solvers(std::vector<SolverEntry>& v) {
  using namespace newton_detail;
  auto reduced = [&](const char* name, const char* summary, LocalSolveFunction solve,
                     bool hybrid = false) {
    SolverEntry e = newton_entry(name, summary, hybrid);
    e.solve_local = std::move(solve);
    v.push_back(std::move(e));
  };
  auto global = [&](const char* name, const char* summary, GlobalSolveFunction solve) {
    SolverEntry e = newton_entry(name, summary);
    e.solve_global = std::move(solve);
    v.push_back(std::move(e));
  };
  reduced("nsn-ac", "semismooth Newton, Alart-Curnier function (NSN-AC)",
          reduced_solver<AlartCurnierFunction>(false));
  reduced("nsn-jm", "semismooth Newton, Jean-Moreau function (NSN-JM)",
          reduced_solver<JeanMoreauFunction>(false));
  reduced("nsn-nm", "semismooth Newton, natural map (NSN-NM)",
          reduced_solver<NaturalMapFunction>(false));
  reduced("nsn-fb", "semismooth Newton, SOCCP Fischer-Burmeister function (NSN-FB)",
          reduced_solver<FischerBurmeisterFunction>(false));
  reduced("nsn-ac-hybrid", "NSN-AC, falling back on Gauss-Seidel sweeps when Newton stalls",
          reduced_solver<AlartCurnierFunction>(true), /*hybrid=*/true);
  global("nsn-ac-global", "NSN-AC on FC/I in (v, r), without forming W",
         global_solver<AlartCurnierFunction>());
  global("nsn-jm-global", "NSN-JM on FC/I in (v, r), without forming W",
         global_solver<JeanMoreauFunction>());
  global("nsn-nm-global", "NSN-NM on FC/I in (v, r), without forming W",
         global_solver<NaturalMapFunction>());
  global("nsn-fb-global", "NSN-FB on FC/I in (v, r), without forming W",
         global_solver<FischerBurmeisterFunction>());
}

}  // namespace registry
}  // namespace fcsolve
