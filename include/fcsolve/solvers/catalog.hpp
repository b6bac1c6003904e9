// The catalogue of every solver fcsolve ships, by name. Each family adds
// its entries in its own header (solvers/*_entries.hpp); this file lists the
// families. Including it instantiates every registered solver, so only
// programs that need run-time selection (CLI, Python, benchmarks) include it.
//
// With FCSOLVE_CATALOG_COMPILED defined (CMake target fcsolve_catalog sets
// it for whatever links it), the families are not instantiated here but in
// src/catalog.cpp, compiled once for the CLI, the Python module, the tests
// and the benchmarks: each program that included the catalogue compiled it
// again, 3 minutes a time on two cores. Every file of a program must see the
// same mode.
#pragma once

#include <fcsolve/solvers/registry.hpp>
#ifdef FCSOLVE_CATALOG_COMPILED
#include <fcsolve/solvers/catalog_compiled.hpp>
#else
#include <fcsolve/solvers/admm_entries.hpp>
#include <fcsolve/solvers/auto_entries.hpp>
#include <fcsolve/solvers/fixed_point_entries.hpp>
#include <fcsolve/solvers/nsgs_entries.hpp>
#include <fcsolve/solvers/ipm_entries.hpp>
#include <fcsolve/solvers/newton_entries.hpp>
#include <fcsolve/solvers/ppa_entries.hpp>
#include <fcsolve/solvers/vi_entries.hpp>
#endif

#include <memory>
#include <mutex>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace fcsolve {
namespace registry {

#ifdef FCSOLVE_CATALOG_COMPILED
namespace families = ::fcsolve::registry::compiled;  // src/catalog.cpp
#else
namespace families = ::fcsolve::registry;  // solvers/*_entries.hpp, inline
#endif

inline const std::vector<SolverEntry>& entries() {
  static const std::vector<SolverEntry> all = [] {
    std::vector<SolverEntry> v;
    // Each solver family appends its entries here.
    families::add_nsgs_solvers(v);
    families::add_vi_solvers(v);
    families::add_newton_solvers(v);
    families::add_ipm_solvers(v);
    families::add_ppa_solvers(v);
    families::add_fixed_point_solvers(v);
    families::add_admm_solvers(v);
    // `auto` runs the entries above by name (solvers/auto_entries.hpp).
    families::add_auto_solvers(v);
    return v;
  }();
  return all;
}

inline const SolverEntry& find(std::string_view name) {
  // Built once, like entries(): a scan comparing names cost about 600
  // instructions a call, and `auto` looks up its first stage on every solve.
  static const std::unordered_map<std::string_view, const SolverEntry*> index = [] {
    std::unordered_map<std::string_view, const SolverEntry*> m;
    for (const auto& e : entries()) m.emplace(e.name, &e);
    return m;
  }();
  if (const auto it = index.find(name); it != index.end()) return *it->second;
  std::string list;
  for (const auto& e : entries()) list += (list.empty() ? "" : ", ") + e.name;
  throw UsageError("unknown solver '" + std::string(name) + "'" +
                   (list.empty() ? std::string(" (no solver is registered)")
                                 : " (available: " + list + ")"));
}

/// The default settings of an entry of entries(), built on first use and
/// kept: copying them costs a pointer (SettingValues shares its map until
/// set), building them 3.1k instructions for nsgs' ten settings (measured).
/// Per entry, so that a one-solve process builds only its own.
inline const SettingValues& default_settings(const SolverEntry& e) {
  static std::mutex mutex;
  static std::vector<std::unique_ptr<const SettingValues>> built(entries().size());
  const auto k = static_cast<std::size_t>(&e - entries().data());
  std::lock_guard<std::mutex> lock(mutex);
  if (!built[k]) built[k] = std::make_unique<const SettingValues>(e.settings);
  return *built[k];
}

inline SolveOutcome solve(const LocalProblemView& p, const std::string& name,
                          const SolveRequest& req) {
  return solve(p, find(name), req);
}
template <class Backend = DefaultBackend>
SolveOutcome solve(const GlobalProblemView& p, const std::string& name, const SolveRequest& req) {
  return solve<Backend>(p, find(name), req);
}

}  // namespace registry
}  // namespace fcsolve
