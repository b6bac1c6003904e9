// Catalogue entries of the NSGS / PSOR family (solvers/registry.hpp): one
// entry per local solver, all with the NSGS knobs (omega, ordering, seed,
// threads, error_every, freezing, extrapolate) plus the local solver's own.
//
// The storage is chosen at run time (solvers/dispatch.hpp): DenseStorage up
// to kDenseStorageMaxContacts contacts, BlockSparseStorage beyond; the cone
// by the contact dimension. That is 2 x 2 instantiations of Nsgs per local solver
// (3D, 2D), plus two shared by every entry for frictionless problems.
#pragma once

#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/nsgs.hpp>
#include <fcsolve/solvers/dispatch.hpp>
#include <fcsolve/solvers/registry.hpp>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace fcsolve {
namespace registry {
namespace nsgs_detail {

/// The NSGS knobs' defaults (the local solver's settings do not matter here).
struct NoLocalSettings {};
inline const NsgsSettings<NoLocalSettings> kDefaults{};

inline std::vector<SettingSpec> common_settings(double omega) {
  const auto& d = kDefaults;
  return {
      real_setting("omega", omega, "over-relaxation r <- omega r_local + (1 - omega) r, in (0, 2)",
                   1e-6, 2 - 1e-6),
      enum_setting("ordering", d.ordering,
                   "contact order: natural, shuffled once, reshuffled every sweep, colour "
                   "by colour (contacts of a colour in parallel), or by increasing load once "
                   "the loads form (then from the start again)"),
      boolean_setting("shuffle", false, "same as --ordering shuffle"),
      integer_setting("seed", d.seed, "seed of the contact shuffles", 0, 4294967295.0),
      integer_setting("threads", d.threads,
                      "OpenMP threads of --ordering coloured (same iterates for any number)", 1,
                      1024),
      integer_setting("stall_sweeps", d.stall_sweeps,
                      "reshuffle every sweep after this many sweeps without 1% progress (0: never)",
                      0, 1e9),
      integer_setting("give_up_sweeps", d.give_up_sweeps,
                      "after that reshuffle, stop (stalled) after this many sweeps without 1% "
                      "progress (0: never)",
                      0, 1e9),
      integer_setting("error_every", d.error_every, "full error at least every k sweeps", 1, 1e9),
      integer_setting("freezing", d.freezing,
                      "skip a contact for k sweeps once its local solution stops moving (0: off)",
                      0, 1e9),
      real_setting("freeze_tol", d.freeze_tol,
                   "relative move ||dr|| / ||r|| at or below which a contact counts as not moving",
                   0, 1),
      boolean_setting("extrapolate", d.extrapolate,
                      "Aitken extrapolation when sweeps converge linearly (kept only if it "
                      "lowers the FCLIB error)"),
  };
}

template <class Settings>
void apply_common(const SolveRequest& req, Settings& s) {
  static_cast<SolverSettings&>(s) = req.common;
  const SettingValues& v = req.settings;
  s.omega = v.real("omega");
  s.ordering = v.enumerated<ContactOrdering>("ordering");
  if (s.ordering == ContactOrdering::Natural && v.boolean("shuffle"))
    s.ordering = ContactOrdering::ShuffledOnce;
  s.seed = static_cast<std::uint32_t>(v.integer("seed"));
  s.threads = static_cast<int>(v.integer("threads"));
  s.stall_sweeps = static_cast<int>(v.integer("stall_sweeps"));
  s.give_up_sweeps = static_cast<int>(v.integer("give_up_sweeps"));
  s.error_every = static_cast<int>(v.integer("error_every"));
  s.freezing = static_cast<int>(v.integer("freezing"));
  s.freeze_tol = v.real("freeze_tol");
  s.extrapolate = v.boolean("extrapolate");
}

/// The solver's settings from the request. Reading a dozen settings by name
/// cost about 2.1k instructions a solve, a fifth of what `auto` adds to
/// NSGS' own time on one contact (callgrind); a request whose values are
/// the map read last by this thread for this entry configuration (the
/// entry's defaults, or one request reused: `auto`'s stages, hot loops)
/// reuses what was read then. Holding the map keeps it from changing.
template <class Settings, class Configure>
void read_settings(const SolveRequest& req, const Configure& configure, Settings& s) {
  struct Read {
    std::shared_ptr<const SettingValues::Map> values;
    Settings settings;
  };
  static thread_local Read last;
  std::shared_ptr<const SettingValues::Map> values = req.settings.shared_values();
  if (!values || values != last.values) {
    last.values.reset();  // until the read succeeds (it throws on a bad value)
    apply_common(req, last.settings);
    configure(req.settings, last.settings.local);
    static_cast<SolverSettings&>(last.settings) = SolverSettings();  // the request's own, below
    last.values = std::move(values);
  }
  s = last.settings;
  static_cast<SolverSettings&>(s) = req.common;
}

template <class Solver, class Configure>
SolveOutcome run(const LocalProblemView& view, const SolveRequest& req, const Configure& configure) {
  static_assert(satisfies_solver_contract_v<Solver, LocalProblemView>);
  Solver solver;
  read_settings(req, configure, solver.settings());
  compute_within_time(solver, view);
  SolveOutcome out;
  out.r = initial_reactions(req, view.size());
  out.u.resize(view.size());
  solver.solve(out.r, out.u);
  out.info = solver.info();
  return out;
}

/// NSGS with local solver Local<Cone>, the cone and the storage picked by
/// the catalogue's dispatch (solvers/dispatch.hpp).
/// `configure(values, local_settings)` copies the local solver's knobs.
/// Frictionless problems use the projection whatever the entry: with rho =
/// 1 / W^aa it is the exact one-contact solution max(0, -q / W^aa), which
/// every local solver computes, so one instantiation serves them all.
template <template <class> class Local, class Configure>
SolveOutcome solve_with(const LocalProblemView& view, const SolveRequest& req,
                        const Configure& configure) {
  return dispatch_cone_and_storage<BlockSparseStorage>(view, [&](auto types) {
    using Cone = typename decltype(types)::Cone;
    using Storage = typename decltype(types)::Storage;
    if constexpr (Cone::dim == 1) {
      const auto defaults = [](const SettingValues&, auto&) {};
      return run<Nsgs<Cone, Storage, local::Projection<Cone>>>(view, req, defaults);
    } else {
      return run<Nsgs<Cone, Storage, Local<Cone>>>(view, req, configure);
    }
  });
}

template <template <class> class Local, class Configure>
SolverEntry make_entry(std::string name, std::string summary, std::vector<SettingSpec> local,
                       Configure configure, double omega = kDefaults.omega) {
  SolverEntry e(std::move(name), "nsgs", std::move(summary));
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
  s.search.line_search = v.enumerated<LineSearch>("line_search");
};
inline const auto configure_hybrid = [](const SettingValues& v, auto& s) {
  configure_newton(v, s.newton);
  s.projection.max_iter = static_cast<int>(v.integer("projection_max_iter"));
};

// The local solvers' defaults are those of their Settings structs; the
// cone does not change them.
using NewtonDefaults = local::AlartCurnierNewton<Coulomb3D>::Settings;
using ProjectionDefaults = local::Projection<Coulomb3D>::Settings;
using ProjectionIterativeDefaults = local::ProjectionIterative<Coulomb3D>::Settings;

inline std::vector<SettingSpec> newton_settings() {
  const NewtonDefaults d;
  return {real_setting("local_tol", d.tol, "local Newton tolerance on ||G||", 0, 1),
          integer_setting("local_max_iter", d.max_iter, "local Newton iterations", 1, 1e6),
          enum_setting("line_search", d.search.line_search, "line search of the local Newton")};
}

inline std::vector<SettingSpec> projection_settings() {
  return {real_setting("rho_scale", ProjectionDefaults().rho_scale,
                       "projection step rho = rho_scale / lambda_max(W^aa)", 1e-6, 1.99)};
}

inline std::vector<SettingSpec> projection_iterative_settings() {
  const ProjectionIterativeDefaults d;
  return {real_setting("local_tol", d.tol, "local residual tolerance (relative to ||qhat||)", 0, 1),
          integer_setting("local_max_iter", d.max_iter, "local iterations", 1, 1e6),
          real_setting("regularization", d.regularization, "proximal weight / lambda_max(W^aa)", 0,
                       1e6)};
}

inline std::vector<SettingSpec> hybrid_settings() {
  std::vector<SettingSpec> v = newton_settings();
  v.push_back(integer_setting("projection_max_iter",
                              local::Hybrid<Coulomb3D>::Settings().projection.max_iter,
                              "iterations of the projection fallback", 1, 1e6));
  return v;
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
      projection_iterative_settings(), configure_projection_iterative));
  v.push_back(make_entry<local::Enumerative>(
      "nsgs-exact", "nonsmooth Gauss-Seidel, exact one-contact solution by enumeration",
      // Off here, unlike the struct's fast mode that "nsgs" runs: this
      // entry is the full enumeration.
      {boolean_setting("newton_first", false,
                       "try Newton on the sliding direction before the full enumeration")},
      configure_enumerative));
  v.push_back(make_entry<local::AlartCurnierNewton>(
      "nsgs-ac", "nonsmooth Gauss-Seidel, local Alart-Curnier semismooth Newton",
      newton_settings(), configure_newton));
  v.push_back(make_entry<local::FischerBurmeisterNewton>(
      "nsgs-fb", "nonsmooth Gauss-Seidel, local Fischer-Burmeister semismooth Newton",
      newton_settings(), configure_newton));
  v.push_back(make_entry<local::Hybrid>(
      "nsgs-hybrid", "nonsmooth Gauss-Seidel, local Newton with a projection fallback",
      hybrid_settings(), configure_hybrid));
  // omega = 1.5: over-relaxation helps every rigid problem of the shared
  // set (1.5 beat 0.8 and 1.2 on all of them); FEM problems may want < 1.
  v.push_back(make_entry<local::Projection>(
      "psor", "projected successive over-relaxation (NSGS, one projection step, omega)",
      projection_settings(), configure_projection, 1.5));
}

}  // namespace registry
}  // namespace fcsolve
