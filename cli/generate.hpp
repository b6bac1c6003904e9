// `fcsolve generate SCENE ...`: writes an FCLIB problem taken along a
// simulated trajectory of one of the scenes of include/fcsolve/scenes/.
// The parsing of the options is main.cpp's; this is the engine.
#pragma once

#include <string>
#include <vector>

namespace fcsolve_cli {

struct GenerateRequest {
  std::string scene;
  long contacts = 100;       ///< target number of contacts of the snapshot
  long seed = 1;
  double mu = 0.5;
  double mass_ratio = -1;    ///< < 0: the scene's default
  double penetration_correction = 0;  ///< beta of contact_law.hpp
  long steps = 0;            ///< 0: the scene's default
  std::string out, local_out;
};

/// The scene names, in the order of the usage text.
const std::vector<std::string>& scene_names();

/// Checks the request (UsageError on a bad value), runs the trajectory,
/// writes the snapshot, prints one key=value line. Returns the exit code
/// (1: no step had a contact, nothing written).
int generate(const GenerateRequest& request);

}  // namespace fcsolve_cli
