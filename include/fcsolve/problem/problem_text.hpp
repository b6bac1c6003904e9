// The FCLIB "info" strings of a problem.
#pragma once

#include <string>

namespace fcsolve {

struct ProblemText {
  std::string title;
  std::string description;
  std::string math_info;
};

}  // namespace fcsolve
