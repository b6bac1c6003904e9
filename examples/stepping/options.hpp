// Command-line options of the time-stepping examples (mbs_pile, fem_contact):
// "--name value" pairs and "--flag" switches, nothing more.
#pragma once

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace stepping {

class Options {
 public:
  Options(int argc, char** argv) : args_(argv + 1, argv + argc), used_(args_.size(), false) {}

  /// True when --name is present (and marks it used).
  bool flag(const std::string& name) {
    for (std::size_t i = 0; i < args_.size(); ++i)
      if (args_[i] == "--" + name) return used_[i] = true;
    return false;
  }

  /// The `count` words that follow --name, or an empty vector when absent.
  std::vector<std::string> values(const std::string& name, std::size_t count = 1) {
    for (std::size_t i = 0; i < args_.size(); ++i) {
      if (args_[i] != "--" + name) continue;
      if (i + count >= args_.size())
        throw std::invalid_argument("--" + name + " needs " + std::to_string(count) + " value(s)");
      std::vector<std::string> out;
      for (std::size_t k = 0; k <= count; ++k) used_[i + k] = true;
      for (std::size_t k = 1; k <= count; ++k) out.push_back(args_[i + k]);
      return out;
    }
    return {};
  }

  double real(const std::string& name, double fallback) {
    const auto v = values(name);
    return v.empty() ? fallback : to_real(name, v[0]);
  }
  long integer(const std::string& name, long fallback) {
    const auto v = values(name);
    return v.empty() ? fallback : to_integer(name, v[0]);
  }
  std::string text(const std::string& name, const std::string& fallback) {
    const auto v = values(name);
    return v.empty() ? fallback : v[0];
  }

  /// Throws on any argument no query consumed (a typo must not run silently).
  void expect_all_used() const {
    for (std::size_t i = 0; i < args_.size(); ++i)
      if (!used_[i]) throw std::invalid_argument("unknown argument '" + args_[i] + "'");
  }

  static double to_real(const std::string& name, const std::string& s) {
    char* end = nullptr;
    const double x = std::strtod(s.c_str(), &end);
    if (s.empty() || *end != '\0') throw std::invalid_argument("--" + name + ": '" + s + "' is not a number");
    return x;
  }
  static long to_integer(const std::string& name, const std::string& s) {
    char* end = nullptr;
    const long x = std::strtol(s.c_str(), &end, 10);
    if (s.empty() || *end != '\0') throw std::invalid_argument("--" + name + ": '" + s + "' is not an integer");
    return x;
  }

 private:
  std::vector<std::string> args_;
  std::vector<bool> used_;
};

}  // namespace stepping
