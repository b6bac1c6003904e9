// Catalogue entries of the NSGS / PSOR family (solvers/registry.hpp): one
// entry per local solver, all with the NSGS knobs (omega, ordering, seed,
// error_every, freezing) plus the local solver's own.
//
// The storage is chosen at run time: DenseStorage up to
// kDenseStorageMaxContacts contacts, BlockSparseStorage beyond; the cone by
// dispatch_cone(d). That is 2 x 2 instantiations of Nsgs per local solver
// (3D, 2D), plus two shared by every entry for frictionless problems.
#pragma once

#include <fcsolve/nsgs.hpp>
#include <fcsolve/solvers/registry.hpp>

#include <string>
#include <utility>
#include <vector>

namespace fcsolve {
namespace registry {
namespace nsgs_detail {

inline std::vector<SettingSpec> common_settings(double omega) {
  return {
      real_setting("omega", omega, "over-relaxation r <- omega r_local + (1 - omega) r, in (0, 2)",
                   1e-6, 2 - 1e-6),
      choice_setting("ordering", "natural", {"natural", "shuffle", "reshuffle"},
                     "contact order: natural, shuffled once, reshuffled every sweep"),
      boolean_setting("shuffle", false, "same as --ordering shuffle"),
      integer_setting("seed", 0, "seed of the contact shuffles", 0, 4294967295.0),
      integer_setting("stall_sweeps", 5000,
                      "reshuffle every sweep after this many sweeps without 1% progress (0: never)",
                      0, 1e9),
      integer_setting("error_every", 10, "full error at least every k sweeps", 1, 1e9),
      integer_setting("freezing", 10,
                      "skip a contact for k sweeps once its local solution stops moving (0: off)",
                      0, 1e9),
  };
}

template <class Settings>
void apply_common(const SolveRequest& req, Settings& s) {
  static_cast<SolverSettings&>(s) = req.common;
  const SettingValues& v = req.settings;
  s.omega = v.real("omega");
  const std::string& o = v.choice("ordering");
  s.ordering = o == "reshuffle" ? ContactOrdering::ShuffledEachSweep
               : o == "shuffle" || v.boolean("shuffle") ? ContactOrdering::ShuffledOnce
                                                        : ContactOrdering::Natural;
  s.seed = static_cast<std::uint32_t>(v.integer("seed"));
  s.stall_sweeps = static_cast<int>(v.integer("stall_sweeps"));
  s.error_every = static_cast<int>(v.integer("error_every"));
  s.freezing = static_cast<int>(v.integer("freezing"));
}

template <class Solver, class Configure>
SolveOutcome run(const LocalProblemView& view, const SolveRequest& req, const Configure& configure) {
  Solver solver;
  apply_common(req, solver.settings());
  configure(req.settings, solver.settings().local);
  solver.compute(view);
  SolveOutcome out;
  out.r = initial_reactions(req, view.size());
  out.u.resize(view.size());
  solver.solve(out.r, out.u);
  out.info = solver.info();
  return out;
}

/// NSGS with local solver Local<Cone>, the cone and the storage picked here.
/// `configure(values, local_settings)` copies the local solver's knobs.
/// Frictionless problems use the projection whatever the entry: with rho =
/// 1 / W^aa it is the exact one-contact solution max(0, -q / W^aa), which
/// every local solver computes, so one instantiation serves them all.
template <template <class> class Local, class Configure>
SolveOutcome solve_with(const LocalProblemView& view, const SolveRequest& req,
                        const Configure& configure) {
  return dispatch_cone(view.d, [&](auto cone) {
    using Cone = decltype(cone);
    constexpr int D = Cone::dim;
    if constexpr (D == 1) {
      const auto defaults = [](const SettingValues&, auto&) {};
      if (view.num_contacts() <= kDenseStorageMaxContacts)
        return run<Nsgs<Cone, DenseStorage<1>, local::Projection<Cone>>>(view, req, defaults);
      return run<Nsgs<Cone, BlockSparseStorage<1>, local::Projection<Cone>>>(view, req, defaults);
    } else {
      if (view.num_contacts() <= kDenseStorageMaxContacts)
        return run<Nsgs<Cone, DenseStorage<D>, Local<Cone>>>(view, req, configure);
      return run<Nsgs<Cone, BlockSparseStorage<D>, Local<Cone>>>(view, req, configure);
    }
  });
}

template <template <class> class Local, class Configure>
SolverEntry make_entry(std::string name, std::string summary, std::vector<SettingSpec> local,
                       Configure configure, double omega = 1.0) {
  SolverEntry e;
  e.name = std::move(name);
  e.family = "nsgs";
  e.summary = std::move(summary);
  e.settings = common_settings(omega);
  e.settings.insert(e.settings.end(), local.begin(), local.end());
  e.default_max_iter = 1000000;
  e.solve_local = [configure](const LocalProblemView& view, const SolveRequest& req) {
    return solve_with<Local>(view, req, configure);
  };
  return e;
}

inline const auto configure_projection = [](const SettingValues& v, auto& s) {
  s.rho_scale = v.real("rho_scale");
};
inline const auto configure_projection_iterative = [](const SettingValues& v, auto& s) {
  s.tol = v.real("local_tol");
  s.max_iter = static_cast<int>(v.integer("local_max_iter"));
  s.regularization = v.real("regularization");
};
inline const auto configure_nothing = [](const SettingValues&, auto&) {};
inline const auto configure_enumerative = [](const SettingValues& v, auto& s) {
  s.newton_first = v.boolean("newton_first");
};

inline const auto configure_newton = [](const SettingValues& v, auto& s) {
  s.tol = v.real("local_tol");
  s.max_iter = static_cast<int>(v.integer("local_max_iter"));
  const std::string& ls = v.choice("line_search");
  s.search.line_search = ls == "armijo" ? LineSearch::Armijo
                         : ls == "none" ? LineSearch::None
                                        : LineSearch::GoldsteinPrice;
};
inline const auto configure_hybrid = [](const SettingValues& v, auto& s) {
  configure_newton(v, s.newton);
  s.projection.max_iter = static_cast<int>(v.integer("projection_max_iter"));
};

inline std::vector<SettingSpec> newton_settings() {
  return {real_setting("local_tol", 1e-14, "local Newton tolerance on ||G||", 0, 1),
          integer_setting("local_max_iter", 20, "local Newton iterations", 1, 1e6),
          choice_setting("line_search", "goldstein-price", {"goldstein-price", "armijo", "none"},
                         "line search of the local Newton")};
}

inline std::vector<SettingSpec> projection_settings() {
  return {real_setting("rho_scale", 1.0, "projection step rho = rho_scale / lambda_max(W^aa)", 1e-6,
                       1.99)};
}

}  // namespace nsgs_detail

inline void add_nsgs_solvers(std::vector<SolverEntry>& v) {
  using namespace nsgs_detail;
  v.push_back(make_entry<local::Enumerative>(
      "nsgs", "nonsmooth Gauss-Seidel, exact one-contact solutions (fast enumeration)", {},
      configure_nothing));
  v.push_back(make_entry<local::Projection>(
      "nsgs-proj", "nonsmooth Gauss-Seidel, one projection step per contact (rho from W^aa)",
      projection_settings(), configure_projection));
  v.push_back(make_entry<local::ProjectionIterative>(
      "nsgs-proj-iter", "nonsmooth Gauss-Seidel, projection iterated to local convergence",
      {real_setting("local_tol", 1e-12, "local residual tolerance (relative to ||qhat||)", 0, 1),
       integer_setting("local_max_iter", 100, "local iterations", 1, 1e6),
       real_setting("regularization", 0.0, "proximal weight / lambda_max(W^aa)", 0, 1e6)},
      configure_projection_iterative));
  v.push_back(make_entry<local::Enumerative>(
      "nsgs-exact", "nonsmooth Gauss-Seidel, exact one-contact solution by enumeration",
      {boolean_setting("newton_first", false,
                       "try Newton on the sliding direction before the full enumeration")},
      configure_enumerative));
  v.push_back(make_entry<local::AlartCurnierNewton>(
      "nsgs-ac", "nonsmooth Gauss-Seidel, local Alart-Curnier semismooth Newton",
      newton_settings(), configure_newton));
  v.push_back(make_entry<local::FischerBurmeisterNewton>(
      "nsgs-fb", "nonsmooth Gauss-Seidel, local Fischer-Burmeister semismooth Newton",
      newton_settings(), configure_newton));
  {
    std::vector<SettingSpec> hybrid = newton_settings();
    hybrid.push_back(integer_setting("projection_max_iter", 200,
                                     "iterations of the projection fallback", 1, 1e6));
    v.push_back(make_entry<local::Hybrid>(
        "nsgs-hybrid", "nonsmooth Gauss-Seidel, local Newton with a projection fallback",
        std::move(hybrid), configure_hybrid));
  }
  // omega = 1.5: over-relaxation helps every rigid problem of the shared
  // set (1.5 beat 0.8 and 1.2 on all of them); FEM problems may want < 1.
  v.push_back(make_entry<local::Projection>(
      "psor", "projected successive over-relaxation (NSGS, one projection step, omega)",
      projection_settings(), configure_projection, 1.5));
}

}  // namespace registry
}  // namespace fcsolve
