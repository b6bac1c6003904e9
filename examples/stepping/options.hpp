// Command-line options of the time-stepping examples (mbs_pile, fem_contact):
// "--name value" pairs and "--flag" switches, nothing more.
#pragma once

#include <fcsolve/scenes/contact_law.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>
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

/// --dump STEP FILE [--dump-local FILE]: which step's problem to write, and
/// where (stepping/dump.hpp writes it).
struct DumpRequest {
  long step = -1;  ///< -1: no dump
  std::string file, local_file;

  void read(Options& o) {
    const auto dump = o.values("dump", 2);
    if (!dump.empty()) {
      step = Options::to_integer("dump", dump[0]);
      file = dump[1];
    }
    local_file = o.text("dump-local", "");
    if (!local_file.empty() && step < 0) throw std::invalid_argument("--dump-local needs --dump STEP FILE");
#ifndef FCSOLVE_EXAMPLES_WITH_FCLIB
    if (step >= 0) throw std::invalid_argument("--dump needs HDF5: build with the fcsolve::fclib target");
#endif
  }
};

/// The options every time-stepping example takes: the Moreau-Jean scheme
/// (steps, --dt, --theta), the contact law, the solver's tolerance and
/// iteration cap, warm start, output and --dump. An example's Parameters
/// derive from it, set their own defaults, and read their scene's options.
struct SteppingParameters {
  long steps = 100, max_iter = 200;
  double mu = 0.5, theta = 0.5, h = 1e-3, tol = 1e-8;
  fcsolve::scenes::ContactLaw law;
  bool warm_start = true, quiet = false;
  DumpRequest dump;

  /// Reads the options above (--restitution only where the scene has impacts)
  /// and checks their ranges.
  void read(Options& o, bool with_restitution) {
    steps = o.integer("steps", steps);
    mu = o.real("mu", mu);
    theta = o.real("theta", theta);
    h = o.real("dt", h);
    tol = o.real("tol", tol);
    max_iter = o.integer("max-iter", max_iter);
    if (with_restitution) law.restitution = o.real("restitution", law.restitution);
    law.beta = o.real("beta", law.beta);
    law.slop = o.real("slop", law.slop);
    warm_start = !o.flag("no-warm-start");
    quiet = o.flag("quiet");
    dump.read(o);
    if (steps < 1 || max_iter < 1) throw std::invalid_argument("--steps and --max-iter must be positive");
    if (!(theta >= 0.5 && theta <= 1.0)) throw std::invalid_argument("--theta must be in [1/2, 1]");
    if (!(h > 0) || !(tol > 0) || !(mu >= 0))
      throw std::invalid_argument("--dt and --tol must be positive, --mu not negative");
  }
};

/// The main() of a time-stepping example: parse the command line, run, and
/// exit 2 when the command line is wrong, 3 when the run throws, else with
/// what run returns.
template <class Parse, class Run>
int example_main(const char* name, int argc, char** argv, Parse parse, Run run) {
  decltype(parse(argc, argv)) parameters;
  try {
    parameters = parse(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
    return 2;
  }
  try {
    return run(parameters);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
    return 3;
  }
}

}  // namespace stepping
