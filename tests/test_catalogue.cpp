// The one test file that instantiates the whole catalogue (test_catalogue.hpp).
#include "test_catalogue.hpp"

#include <fcsolve/solvers/catalog.hpp>

namespace fcsolve_test {

const std::vector<fcsolve::registry::SolverEntry>& catalogue_entries() {
  return fcsolve::registry::entries();
}
const fcsolve::registry::SolverEntry& catalogue_find(const std::string& name) {
  return fcsolve::registry::find(name);
}
const fcsolve::registry::SettingValues& catalogue_default_settings(const fcsolve::registry::SolverEntry& e) {
  return fcsolve::registry::default_settings(e);
}

}  // namespace fcsolve_test
