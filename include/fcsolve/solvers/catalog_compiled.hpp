// The catalogue compiled once (FCSOLVE_CATALOG_COMPILED; see
// solvers/catalog.hpp): defined in src/catalog.cpp (CMake target
// fcsolve_catalog), each appends its family's entries as the inline
// add_*_solvers of solvers/<family>_entries.hpp do.
#pragma once

#include <fcsolve/solvers/registry.hpp>

#include <vector>

namespace fcsolve {
namespace registry {
namespace compiled {

void add_nsgs_solvers(std::vector<SolverEntry>& v);
void add_vi_solvers(std::vector<SolverEntry>& v);
void add_newton_solvers(std::vector<SolverEntry>& v);
void add_ipm_solvers(std::vector<SolverEntry>& v);
void add_ppa_solvers(std::vector<SolverEntry>& v);
void add_fixed_point_solvers(std::vector<SolverEntry>& v);
void add_admm_solvers(std::vector<SolverEntry>& v);
void add_auto_solvers(std::vector<SolverEntry>& v);

}  // namespace compiled
}  // namespace registry
}  // namespace fcsolve
