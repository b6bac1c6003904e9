// Catalogue entries of the proximal point family (ppa.hpp):
//   ppa        inner semismooth Newton, Alart-Curnier function (Siconos' PROX)
//   ppa-nsgs   inner NSGS with exact one-contact solutions
//   ppa-global FC/I natively in (v, r), inner global Newton (Alart-Curnier)
//              with a contact compliance alpha; global-only, as nsn-ac-global
//              (FC/I with bilateral constraints: ppa on the reduced form)
// Small scenes (<= kDenseStorageMaxContacts contacts) store W dense (and
// Newton factorises with a dense LU), the others sparse, as the inner
// solver's own entries do.
#pragma once

#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/ppa.hpp>
#include <fcsolve/solvers/dispatch.hpp>
#include <fcsolve/solvers/registry.hpp>

#include <string>
#include <utility>
#include <vector>

namespace fcsolve {
namespace registry {
namespace ppa_detail {

/// The outer knobs' defaults (the inner settings do not matter here).
struct NoInnerSettings {};
inline const ProximalPointSettings<NoInnerSettings> kDefaults{};

inline std::vector<SettingSpec> settings_specs() {
  const auto& d = kDefaults;
  return {
      real_setting("sigma", d.sigma, "alpha = sigma err^nu, in units of mean |W_ii|", 1e-12),
      real_setting("nu", d.nu, "exponent of the error in alpha", 0.0, 10.0),
      real_setting("alpha_min", d.alpha_min, "lower bound on alpha (units of mean |W_ii|)", 1e-300),
      real_setting("alpha_max", d.alpha_max, "upper bound on alpha (units of mean |W_ii|)", 1e-300),
      integer_setting("fast_inner_iterations", d.fast_inner_iterations,
                      "an inner solve this short that lowers the error divides alpha's factor by 10", 0, 1e9),
      integer_setting("inner_max_iter", d.inner_max_iter, "iteration cap of each inner solve", 1,
                      1e9),
      integer_setting("inner_stall_window", d.inner_stall_window,
                      "an inner Newton solve whose error does not halve in this many iterations "
                      "fails early (0: Newton's own window; no effect on ppa-nsgs)",
                      0, 1e9),
  };
}

/// The request's outer settings into a ProximalPointSettings.
template <class Settings>
void configure(Settings& s, const SolveRequest& req) {
  static_cast<SolverSettings&>(s) = req.common;
  const SettingValues& v = req.settings;
  s.sigma = v.real("sigma");
  s.nu = v.real("nu");
  s.alpha_min = v.real("alpha_min");
  s.alpha_max = v.real("alpha_max");
  s.fast_inner_iterations = int(v.integer("fast_inner_iterations"));
  s.inner_max_iter = int(v.integer("inner_max_iter"));
  s.inner_stall_window = int(v.integer("inner_stall_window"));
}

template <class Solver>
SolveOutcome run(const LocalProblemView& p, const SolveRequest& req) {
  static_assert(satisfies_solver_contract_v<Solver, LocalProblemView>);
  Solver solver;
  configure(solver.settings(), req);
  return compute_and_solve(solver, p, req);
}

/// ppa with the inner solver Inner<Cone, Storage>, cone and storage from
/// the catalogue's dispatch with `Sparse` beyond the dense threshold.
template <template <class, class> class Inner, template <int> class Sparse>
LocalSolveFunction solver() {
  return [](const LocalProblemView& p, const SolveRequest& req) {
    return dispatch_cone_and_storage<Sparse>(p, [&](auto types) {
      using T = decltype(types);
      using Cone = typename T::Cone;
      return run<ProximalPoint<Cone, Inner<Cone, typename T::Storage>>>(p, req);
    });
  };
}

template <class Cone, class Storage>
using NewtonInner = Newton<AlartCurnierFunction, Cone, Storage>;
template <class Cone, class Storage>
using NsgsInner = Nsgs<Cone, Storage>;

/// ppa-global: FC/I in (v, r); bilateral constraints go through the
/// registry's reduction to ppa (GlobalNewton does not handle G, b).
inline GlobalSolveFunction global_solver() {
  return [](const GlobalProblemView& p, const SolveRequest& req) {
    if (p.has_bilateral())
      return solve_bilateral_by_reduction(p, req, [](const LocalProblemView& reduced, const SolveRequest& within) {
        return solver<NewtonInner, SparseStorage>()(reduced, within);
      });
    return dispatch_cone(p.d, [&](auto cone) {
      using Solver = ProximalPointGlobal<decltype(cone)>;
      static_assert(satisfies_solver_contract_v<Solver, GlobalProblemView>);
      Solver ppa;
      configure(ppa.settings(), req);
      return compute_and_solve(ppa, p, req);
    });
  };
}

inline SolverEntry entry(std::string name, std::string summary) {
  SolverEntry e(std::move(name), "ppa", std::move(summary));
  e.settings = settings_specs();
  e.default_max_iter = kDefaults.max_iter;
  return e;
}

}  // namespace ppa_detail

inline void add_ppa_solvers(std::vector<SolverEntry>& v) {
  using namespace ppa_detail;
  SolverEntry newton = entry("ppa",
                             "proximal point, FC/II(W + alpha I, q - alpha r_k) by semismooth Newton "
                             "(Alart-Curnier) (PROX)");
  newton.solve_local = solver<NewtonInner, SparseStorage>();
  v.push_back(std::move(newton));
  SolverEntry nsgs =
      entry("ppa-nsgs", "proximal point, FC/II(W + alpha I, q - alpha r_k) by NSGS (exact local solutions)");
  nsgs.solve_local = solver<NsgsInner, BlockSparseStorage>();
  v.push_back(std::move(nsgs));
  SolverEntry global = entry("ppa-global",
                             "proximal point on FC/I in (v, r), without forming W: w - alpha r_k and "
                             "compliance alpha, by semismooth Newton (Alart-Curnier)");
  global.solve_global = global_solver();
  v.push_back(std::move(global));
}

}  // namespace registry
}  // namespace fcsolve
