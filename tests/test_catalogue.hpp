// The solver catalogue for the test programs, compiled once
// (test_catalogue.cpp): including solvers/catalog.hpp instantiates every
// registered solver, minutes of compilation per file on two cores, so the
// tests that run entries through the registry see only registry.hpp and
// these three functions.
#pragma once

#include <fcsolve/solvers/registry.hpp>

#include <string>
#include <vector>

namespace fcsolve_test {

/// registry::entries(), registry::find(name), registry::default_settings(e).
const std::vector<fcsolve::registry::SolverEntry>& catalogue_entries();
const fcsolve::registry::SolverEntry& catalogue_find(const std::string& name);
const fcsolve::registry::SettingValues& catalogue_default_settings(const fcsolve::registry::SolverEntry& e);

/// registry::solve(p, entry, req) with the entry found by name.
template <class View>
fcsolve::registry::SolveOutcome solve_named(const View& p, const std::string& name,
                                            const fcsolve::registry::SolveRequest& req) {
  return fcsolve::registry::solve(p, catalogue_find(name), req);
}

}  // namespace fcsolve_test
