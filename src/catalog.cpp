// The compiled catalogue (include/fcsolve/solvers/catalog.hpp,
// FCSOLVE_CATALOG_COMPILED; CMake target fcsolve_catalog): every family's
// entries instantiated in this one file, for the CLI, the Python module, the
// tests and the benchmarks alike. One file, not one per family: compiled
// apart, the families instantiate their shared parts again (a file per
// family took twice the CPU time of this one on the 2-core machine).
#include <fcsolve/solvers/catalog.hpp>

#include <fcsolve/solvers/admm_entries.hpp>
#include <fcsolve/solvers/auto_entries.hpp>
#include <fcsolve/solvers/fixed_point_entries.hpp>
#include <fcsolve/solvers/ipm_entries.hpp>
#include <fcsolve/solvers/newton_entries.hpp>
#include <fcsolve/solvers/nsgs_entries.hpp>
#include <fcsolve/solvers/ppa_entries.hpp>
#include <fcsolve/solvers/vi_entries.hpp>

namespace fcsolve {
namespace registry {
namespace compiled {

void add_nsgs_solvers(std::vector<SolverEntry>& v) { registry::add_nsgs_solvers(v); }
void add_vi_solvers(std::vector<SolverEntry>& v) { registry::add_vi_solvers(v); }
void add_newton_solvers(std::vector<SolverEntry>& v) { registry::add_newton_solvers(v); }
void add_ipm_solvers(std::vector<SolverEntry>& v) { registry::add_ipm_solvers(v); }
void add_ppa_solvers(std::vector<SolverEntry>& v) { registry::add_ppa_solvers(v); }
void add_fixed_point_solvers(std::vector<SolverEntry>& v) { registry::add_fixed_point_solvers(v); }
void add_admm_solvers(std::vector<SolverEntry>& v) { registry::add_admm_solvers(v); }
void add_auto_solvers(std::vector<SolverEntry>& v) { registry::add_auto_solvers(v); }

}  // namespace compiled
}  // namespace registry
}  // namespace fcsolve
