// Catalogue entries of the semismooth Newton family (newton.hpp):
//   nsn-ac, nsn-jm, nsn-nm, nsn-fb         reduced form (FC/II; FC/I by reduction)
//   nsn-ac-hybrid                          + Gauss-Seidel fallback when Newton stalls
//   nsn-ac-global, nsn-jm-global, nsn-nm-global, nsn-fb-global
//                                          FC/I natively in (v, r), W never formed
// Small scenes (<= kDenseStorageMaxContacts contacts) use DenseStorage and a
// dense LU, the others SparseStorage and the default sparse LU (UMFPACK).
#pragma once

#include <fcsolve/newton.hpp>
#include <fcsolve/solvers/registry.hpp>

namespace fcsolve {
namespace registry {

namespace newton_detail {

inline NewtonSettings newton_settings(const SolveRequest& req, bool hybrid) {
  NewtonSettings s;
  static_cast<SolverSettings&>(s) = req.common;
  const SettingValues& v = req.settings;
  const std::string& ls = v.choice("line_search");
  s.line_search = ls == "armijo" ? LineSearch::Armijo
                  : ls == "none" ? LineSearch::None
                                 : LineSearch::GoldsteinPrice;
  const std::string& rho = v.choice("rho_strategy");
  s.rho_strategy = rho == "constant"   ? RhoStrategy::Constant
                   : rho == "spectral" ? RhoStrategy::SpectralNorm
                   : rho == "adaptive" ? RhoStrategy::Adaptive
                                       : RhoStrategy::SplitSpectralNorm;
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

template <template <class> class F, class Cone, class Storage>
SolveOutcome solve_reduced(const LocalProblemView& p, const SolveRequest& req, bool hybrid) {
  Newton<F, Cone, Storage> solver(newton_settings(req, hybrid));
  solver.compute(p);
  SolveOutcome out;
  out.r = initial_reactions(req, p.size());
  out.u.resize(p.size());
  out.info = solver.solve(out.r, out.u);
  return out;
}

template <template <class> class F>
LocalSolveFunction reduced_solver(bool hybrid) {
  return [hybrid](const LocalProblemView& p, const SolveRequest& req) {
    return dispatch_cone(p.d, [&](auto cone) {
      using Cone = decltype(cone);
      if (p.num_contacts() <= kDenseStorageMaxContacts)
        return solve_reduced<F, Cone, DenseStorage<Cone::dim>>(p, req, hybrid);
      return solve_reduced<F, Cone, SparseStorage<Cone::dim>>(p, req, hybrid);
    });
  };
}

/// FC/I in (v, r); problems with bilateral constraints go through the
/// reduction (GlobalNewton does not handle G, b).
template <template <class> class F>
GlobalSolveFunction global_solver() {
  return [](const GlobalProblemView& p, const SolveRequest& req) {
    if (p.has_bilateral()) {
      GlobalReduction<DefaultBackend> reduction(p);
      SolveOutcome out = reduced_solver<F>(false)(reduction.local(), req);
      out.v = reduction.velocity(out.r);
      out.lambda = reduction.multipliers(out.r);
      out.info.message += "; bilateral constraints: solved in the reduced form";
      return out;
    }
    return dispatch_cone(p.d, [&](auto cone) {
      using Cone = decltype(cone);
      GlobalNewton<F, Cone> solver(newton_settings(req, false));
      solver.compute(p);
      SolveOutcome out;
      out.r = initial_reactions(req, p.size());
      out.v.resize(p.num_dofs());
      out.info = solver.solve(out.r, out.v);
      return out;
    });
  };
}

inline std::vector<SettingSpec> newton_settings_specs(bool hybrid) {
  std::vector<SettingSpec> v = {
      choice_setting("line_search", "goldstein-price", {"goldstein-price", "armijo", "none"},
                     "line search on 1/2 ||G||^2"),
      integer_setting("line_search_memory", 10,
                      "nonmonotone Armijo test against the largest of the last N merits (1: monotone)", 1, 16),
      choice_setting("rho_strategy", "split-spectral",
                     {"split-spectral", "spectral", "constant", "adaptive"},
                     "per-contact rho: rho / W_NN and rho / ||W_TT||, rho / ||W^aa||, rho, or "
                     "split-spectral rescaled when Newton stalls"),
      real_setting("rho", 1.0, "the constant rho, or the factor on the spectral values", 1e-12),
      real_setting("levenberg_marquardt", 0.1,
                   "shift (J + delta I), delta = this * max|J_ii| * min(1, ||G|| / ||G(0)||); 0: plain Newton",
                   0.0),
      boolean_setting("nonmonotone", true, "take the full step when the line search fails"),
      integer_setting("stall_window", hybrid ? 20 : 500,
                      "iterations without halving the best error that count as a stall (0: never)", 0),
  };
  if (hybrid) {
    v.push_back(integer_setting("fallback_sweeps", 100, "Gauss-Seidel sweeps per fallback", 1));
    v.push_back(real_setting("resume_ratio", 0.1, "resume Newton once the error dropped by this", 0.0, 1.0));
  }
  return v;
}

}  // namespace newton_detail

inline void add_newton_solvers(std::vector<SolverEntry>& v) {
  using namespace newton_detail;
  const auto settings = newton_settings_specs(false);
  v.push_back({"nsn-ac", "newton", "semismooth Newton, Alart-Curnier function (NSN-AC)", settings,
               false, 1000, reduced_solver<AlartCurnierFunction>(false), {}});
  v.push_back({"nsn-jm", "newton", "semismooth Newton, Jean-Moreau function (NSN-JM)", settings,
               false, 1000, reduced_solver<JeanMoreauFunction>(false), {}});
  v.push_back({"nsn-nm", "newton", "semismooth Newton, natural map (NSN-NM)", settings, false, 1000,
               reduced_solver<NaturalMapFunction>(false), {}});
  v.push_back({"nsn-fb", "newton", "semismooth Newton, SOCCP Fischer-Burmeister function (NSN-FB)",
               settings, false, 1000, reduced_solver<FischerBurmeisterFunction>(false), {}});
  v.push_back({"nsn-ac-hybrid", "newton",
               "NSN-AC, falling back on Gauss-Seidel sweeps when Newton stalls",
               newton_settings_specs(true), false, 5000, reduced_solver<AlartCurnierFunction>(true), {}});
  v.push_back({"nsn-ac-global", "newton", "NSN-AC on FC/I in (v, r), without forming W", settings,
               false, 1000, {}, global_solver<AlartCurnierFunction>()});
  v.push_back({"nsn-jm-global", "newton", "NSN-JM on FC/I in (v, r), without forming W", settings,
               false, 1000, {}, global_solver<JeanMoreauFunction>()});
  v.push_back({"nsn-nm-global", "newton", "NSN-NM on FC/I in (v, r), without forming W", settings,
               false, 1000, {}, global_solver<NaturalMapFunction>()});
  v.push_back({"nsn-fb-global", "newton", "NSN-FB on FC/I in (v, r), without forming W", settings,
               false, 1000, {}, global_solver<FischerBurmeisterFunction>()});
}

}  // namespace registry
}  // namespace fcsolve
