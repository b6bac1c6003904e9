// fcsolve: command-line front end.
//   fcsolve info FILE [--json]
//   fcsolve solve FILE [--solver NAME (auto)] [--tol 1e-8] [--max-iter N] [--max-time S]
//                 [--out SOLUTION.hdf5] [--json] [--history] [--warm-start none|guess|solution]
//                 [--repeat N] [--SETTING VALUE ...]
//   fcsolve error FILE SOLUTION.hdf5 [--json]
//   fcsolve solvers [--json]
//   fcsolve check FILE [--max-time S] [--to-optimum] [--json]   existence (Slater) check and diagnostics
//   fcsolve run FILE... [--solvers a,b,...] [--tol 1e-8] [--max-time S]
//   fcsolve generate SCENE [--contacts N] [--seed S] [--mu X] [--mass-ratio R]
//                 [--penetration-correction B] [--steps K] [--out F.hdf5] [--local-out F.hdf5]
//   fcsolve bench PROBLEMS... [options]  /  fcsolve report DIR   (benchmark
//                 campaigns: forwarded to the Python runner fcsolve.campaign)
// Exit codes: 0 solved (or command done), 1 tolerance not reached, 2 bad input
// or usage (message on stderr), 3 internal error.
#include "field_output.hpp"
#include "generate.hpp"
#include "isolated_read.hpp"
#include "json_writer.hpp"
#include "memory_limit.hpp"

#include <fcsolve/io/fclib.hpp>
#include <fcsolve/nipm.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/problem/report_fields.hpp>
#include <fcsolve/problem/summary.hpp>
#include <fcsolve/solvers/catalog.hpp>
#include <fcsolve/solvers/report_fields.hpp>

#include <unistd.h>

#include <cerrno>
#include <climits>
#include <limits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace fcsolve_cli {
extern const char* const campaign_source_dir;  // generated: cli/source_paths.cpp.in
}  // namespace fcsolve_cli

namespace {

using namespace fcsolve;
using fcsolve_cli::json_fields;
using fcsolve_cli::JsonWriter;
using fcsolve_cli::text_line;
using fcsolve_cli::probe_read_in_child;

constexpr int kExitSolved = 0, kExitNotSolved = 1, kExitBadInput = 2, kExitInternal = 3;

const char* kUsage =
    "usage: fcsolve <command> [options]\n"
    "  info FILE [--json]                       problem summary (key=value or JSON)\n"
    "  solve FILE [--solver NAME] [options]     solve an FCLIB problem (default solver: auto)\n"
    "      --tol X (1e-8)  --max-iter N  --max-time SECONDS  --out FILE.hdf5  --json\n"
    "      --history  --warm-start none|guess|solution  --SETTING VALUE (see `fcsolve solvers`)\n"
    "      --repeat N (1): solve N times in this process, report the fastest (hot loop)\n"
    "  error FILE SOLUTION.hdf5 [--json]        FCLIB error of a stored /solution (r [, v])\n"
    "  solvers [--json]                         list solvers and their settings\n"
    "  check FILE [--max-time S] [--to-optimum] [--json]\n"
    "                                           existence check (Slater SOC program; stops at the\n"
    "                                           first certified witness unless --to-optimum) and\n"
    "                                           diagnostics: d nc / n, rank(H), cond(W)\n"
    "  run FILE... [--solvers a,b] [--tol X] [--max-time S]\n"
    "                                           solve many files, print a table\n"
    "  generate SCENE [--contacts N (100)] [--seed S (1)] [--mu X (0.5)] [--mass-ratio R]\n"
    "        [--penetration-correction B (0)] [--steps K] [--out FILE.hdf5] [--local-out FILE.hdf5]\n"
    "                                           write an FC/I (--out) and/or FC/II (--local-out)\n"
    "                                           problem taken along a simulated trajectory; SCENE:\n"
    "                                           sphere-pile box-stack wall tower mixed-shapes\n"
    "                                           heavy-on-light fem-block fem-two-bodies\n"
    "  bench PROBLEMS... [--solvers all,siconos:nsgs] [--tol 1e-4,1e-8] [--timeout 20]\n"
    "        [--out DIR] [--jobs N] [--dask ADDRESS] [--report]   benchmark campaign (CSV)\n"
    "  report DIR                               charts and HTML page of a campaign\n"
    "  version                                  print the version\n"
    "exit codes: 0 solved, 1 tolerance not reached, 2 bad input or usage, 3 internal error or out of memory\n";

/// Command-line arguments: positionals and --key [value] options.
struct Args {
  std::vector<std::string> positional;
  std::vector<std::pair<std::string, std::optional<std::string>>> options;

  static Args parse(int argc, char** argv, int first) {
    Args a;
    for (int k = first; k < argc; ++k) {
      std::string s = argv[k];
      if (s.rfind("--", 0) == 0 && s.size() > 2) {
        std::string key = s.substr(2);
        std::optional<std::string> value;
        const auto eq = key.find('=');
        if (eq != std::string::npos) {
          value = key.substr(eq + 1);
          key = key.substr(0, eq);
        } else if (k + 1 < argc && !is_option(argv[k + 1])) {
          value = argv[++k];
        }
        a.options.emplace_back(key, value);
      } else {
        a.positional.push_back(s);
      }
    }
    return a;
  }
  static bool is_option(const char* s) {
    // "--x" is an option; "-1e-3" (a negative number) is a value
    return std::strncmp(s, "--", 2) == 0 && std::strlen(s) > 2;
  }
  bool flag(const std::string& key) {
    for (auto it = options.begin(); it != options.end(); ++it)
      if (it->first == key) {
        if (it->second && *it->second != "true" && *it->second != "1") {
          // a flag followed by a positional: give the word back
          positional.push_back(*it->second);
        }
        options.erase(it);
        return true;
      }
    return false;
  }
  std::optional<std::string> take(const std::string& key) {
    for (auto it = options.begin(); it != options.end(); ++it)
      if (it->first == key) {
        if (!it->second) throw UsageError("option --" + key + " needs a value");
        std::string v = *it->second;
        options.erase(it);
        return v;
      }
    return std::nullopt;
  }
  void expect_no_more_options() const {
    if (!options.empty()) throw UsageError("unknown option --" + options.front().first);
  }
};

double parse_double(const std::string& key, const std::string& text) {
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0') throw UsageError("--" + key + ": '" + text + "' is not a number");
  return x;
}
long long parse_int(const std::string& key, const std::string& text) {
  char* end = nullptr;
  const long long x = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0') throw UsageError("--" + key + ": '" + text + "' is not an integer");
  return x;
}

std::string fmt(double x, const char* spec = "%.3e") {
  char buf[40];
  std::snprintf(buf, sizeof buf, spec, x);
  return buf;
}

/// A problem file from the user: probed in a child first (isolated_read.hpp).
fclib::Problem read_untrusted(const std::string& path) {
  probe_read_in_child(path);
  return fclib::read_problem(path);
}

// ---------------------------------------------------------------- info

int cmd_info(Args args) {
  const bool json = args.flag("json");
  args.expect_no_more_options();
  if (args.positional.size() != 1) throw UsageError("info takes exactly one FILE");
  const std::string path = args.positional[0];
  const fclib::Problem problem = read_untrusted(path);
  const ProblemSummary s = std::visit([](const auto& p) { return summarize(p); }, problem);
  const std::string title = std::visit([](const auto& p) { return p.text.title; }, problem);
  Fields fields = summary_fields(s, title);
  fields.insert(fields.begin(), Field::text("file", path));
  if (json) {
    JsonWriter w;
    json_fields(w.begin_object(), fields).end_object();
    std::cout << w.str() << "\n";
  } else {
    std::cout << text_line(fields) << "\n";
  }
  return kExitSolved;
}

// ---------------------------------------------------------------- solve

struct SolveOptions {
  std::string solver;
  registry::SolveRequest request;
  std::string out, warm_start = "none";
  bool json = false;
  /// Solves in this process, the fastest reported: a hot loop for
  /// sub-millisecond problems, where a fresh process' first call costs
  /// more than the solve (the solvers are deterministic: same result).
  int repeat = 1;
};

/// Common options (--tol, --max-iter, ...) and the solver's own settings.
SolveOptions parse_solve_options(Args& args, const std::string& default_solver) {
  SolveOptions o;
  o.json = args.flag("json");
  const bool history = args.flag("history");
  o.solver = args.take("solver").value_or(default_solver);
  const registry::SolverEntry& entry = registry::find(o.solver);
  o.request = registry::make_request(entry);
  // Parsed here, checked by the registry (registry::detail::check_common),
  // as for Python: both accept and reject the same requests.
  long long max_iter = o.request.common.max_iter;
  if (auto v = args.take("tol")) o.request.common.tol = parse_double("tol", *v);
  if (auto v = args.take("max-iter")) max_iter = parse_int("max-iter", *v);
  if (auto v = args.take("max-time")) o.request.common.max_time = parse_double("max-time", *v);
  registry::detail::check_common(o.request.common.tol, max_iter, o.request.common.max_time);
  o.request.common.max_iter = int(max_iter);
  if (auto v = args.take("out")) o.out = *v;
  if (auto v = args.take("warm-start")) o.warm_start = *v;
  if (auto v = args.take("repeat")) {
    const long long n = parse_int("repeat", *v);
    if (n < 1 || n > 1000000) throw UsageError("--repeat must lie in [1, 1000000]");
    o.repeat = int(n);
  }
  if (o.warm_start != "none" && o.warm_start != "guess" && o.warm_start != "solution")
    throw UsageError("--warm-start must be none, guess or solution");
  o.request.common.record_history = history;
  // Everything left must be a setting of this solver (--omega 0.8, --shuffle).
  for (auto& [key, value] : args.options) {
    std::string name = key;
    for (auto& c : name)
      if (c == '-') c = '_';
    if (!o.request.settings.declares(name))
      throw UsageError("unknown option --" + key + " (not a common option nor a setting of '" +
                       o.solver + "'; see `fcsolve solvers`)");
    const registry::SettingSpec* spec = nullptr;
    for (const auto& s : entry.settings)
      if (s.name == name) spec = &s;
    if (!value) {
      if (spec->type != registry::SettingType::Boolean)
        throw UsageError("option --" + key + " needs a value");
      o.request.settings.set(name, true);
    } else {
      o.request.settings.set_text(name, *value);
    }
  }
  args.options.clear();
  return o;
}

void print_outcome(const std::string& path, const std::string& kind,
                   const registry::SolveOutcome& out, const SolveOptions& o) {
  Fields fields = registry::outcome_fields(out, o.request.common.tol);
  fields.insert(fields.begin(), {Field::text("file", path), Field::text("kind", kind, false, ShownInJson)});
  if (o.json) {
    JsonWriter w;
    json_fields(w.begin_object(), fields);
    if (!out.stages.empty()) {  // staged solvers (auto): what each stage did
      w.key("stages").begin_array();
      for (const auto& st : out.stages) json_fields(w.begin_object(), registry::stage_fields(st)).end_object();
      w.end_array();
    }
    if (o.request.common.record_history) {
      w.key("history");
      w.values(out.info.history);
    }
    if (!o.out.empty()) w.field("out", o.out);
    w.end_object();
    std::cout << w.str() << "\n";
    return;
  }
  std::cout << text_line(fields) << "\n";
  if (o.request.common.record_history) {
    std::cout << "history:";
    for (double e : out.info.history) std::cout << " " << fmt(e, "%.3e");
    std::cout << "\n";
  }
}

/// The warm start asked for (--warm-start guess|solution), checked against
/// the problem's sizes so that a mismatch names the file and the dataset.
std::optional<fclib::Solution> warm_start(const std::string& path, const std::string& which,
                                          const fclib::Problem& problem) {
  if (which == "none") return std::nullopt;
  std::optional<fclib::Solution> s;
  std::string group;
  if (which == "solution") {
    s = fclib::read_solution(path);
    group = "solution";
    if (!s) throw IoError(path, group, "--warm-start solution: the file has no /solution");
  } else {
    auto g = fclib::read_guesses(path);
    group = "guesses/1";
    if (g.empty()) throw IoError(path, "guesses", "--warm-start guess: the file has no /guesses");
    s = std::move(g.front());
  }
  const auto [m, n] = std::visit(
      [](const auto& p) -> std::pair<Index, Index> {
        using T = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<T, LocalProblem>) return {p.W.rows(), -1};
        else return {p.H.cols(), p.M.rows()};
      },
      problem);
  const auto check = [&](const Vector& x, const char* name, Index expected) {
    if (expected >= 0 && x.size() > 0 && x.size() != expected)
      throw IoError(path, group + "/" + name,
                    "--warm-start " + which + ": " + std::to_string(x.size()) +
                        " entries, the problem needs " + std::to_string(expected));
  };
  check(s->r, "r", m);
  check(s->v, "v", n);
  return s;
}

/// True when `a` and `b` name the same existing file (links included).
bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  return std::filesystem::equivalent(a, b, ec) && !ec;
}

registry::SolveOutcome solve_file(const std::string& path, const fclib::Problem& problem,
                                  SolveOptions& o) {
  if (auto ws = warm_start(path, o.warm_start, problem)) {
    o.request.r0 = ws->r;
    o.request.v0 = ws->v;
  }
  const auto once = [&] {
    return std::visit(
        [&](const auto& p) {
          using T = std::decay_t<decltype(p)>;
          const auto& entry = registry::find(o.solver);
          if constexpr (std::is_same_v<T, LocalProblem>) return registry::solve(LocalProblemView(p), entry, o.request);
          else return registry::solve(GlobalProblemView(p), entry, o.request);
        },
        problem);
  };
  const auto seconds = [](const registry::SolveOutcome& x) {
    return x.info.setup_seconds + x.info.solve_seconds;
  };
  registry::SolveOutcome best = once();
  for (int k = 1; k < o.repeat; ++k) {
    registry::SolveOutcome again = once();
    if (seconds(again) < seconds(best)) best = std::move(again);
  }
  return best;
}

int cmd_solve(Args args) {
  SolveOptions o = parse_solve_options(args, "auto");
  if (args.positional.size() != 1) throw UsageError("solve takes exactly one FILE");
  const std::string path = args.positional[0];
  // --out rewrites its file from scratch: never the file we read (its
  // guesses and reference solution would be lost).
  if (!o.out.empty() && same_file(path, o.out))
    throw UsageError("--out " + o.out + " is the input file; refusing to overwrite it (its "
                     "/guesses and /solution would be lost): write the solution to another file");
  const fclib::Problem problem = read_untrusted(path);
  const std::string kind = std::holds_alternative<LocalProblem>(problem) ? "local" : "global";
  const registry::SolveOutcome out =
      fclib::with_file_context(path, problem, [&] { return solve_file(path, problem, o); });
  if (!o.out.empty()) {
    fclib::write_problem(o.out, problem);
    fclib::write_solution(o.out, fclib::Solution{out.r, out.u, out.v, out.lambda});
  }
  print_outcome(path, kind, out, o);
  return out.info.converged() ? kExitSolved : kExitNotSolved;
}

// ---------------------------------------------------------------- error

/// The FCLIB error of a stored solution (r [, v]), as fcref.py measures it.
int cmd_error(Args args) {
  const bool json = args.flag("json");
  args.expect_no_more_options();
  if (args.positional.size() != 2) throw UsageError("error takes PROBLEM.hdf5 SOLUTION.hdf5");
  const std::string path = args.positional[0], sol_path = args.positional[1];
  const fclib::Problem problem = read_untrusted(path);
  probe_read_in_child(sol_path, /*with_problem=*/false);
  auto sol = fclib::read_solution(sol_path);
  if (!sol) throw IoError(sol_path, "solution", "missing /solution group");
  Fields fields;
  if (const auto* lp = std::get_if<LocalProblem>(&problem)) {
    if (sol->r.size() != lp->size())
      throw IoError(sol_path, "solution/r", "expected " + std::to_string(lp->size()) + " entries");
    fields = error_fields(local_error_report(*lp, sol->r));
  } else {
    const auto& gp = std::get<GlobalProblem>(problem);
    if (sol->r.size() != gp.size())
      throw IoError(sol_path, "solution/r", "expected " + std::to_string(gp.size()) + " entries");
    GlobalReduction<DefaultBackend> reduction = fclib::with_file_context(
        path, problem, [&] { return GlobalReduction<DefaultBackend>(gp, /*form_W=*/false); });
    const Vector v = sol->v.size() ? sol->v : reduction.velocity(sol->r);
    if (v.size() != gp.num_dofs())
      throw IoError(sol_path, "solution/v", "expected " + std::to_string(gp.num_dofs()) + " entries");
    const Vector lambda = gp.has_bilateral() ? (sol->l.size() ? sol->l : reduction.multipliers(sol->r)) : Vector();
    fields = error_fields(global_error_report(gp, reduction.free_velocity_norm(), sol->r, v, lambda));
  }
  if (json) {
    JsonWriter w;
    w.begin_object().field("file", path).field("solution", sol_path);
    json_fields(w, fields).end_object();
    std::cout << w.str() << "\n";
  } else {
    std::cout << text_line(fields) << "\n";
  }
  return kExitSolved;
}

// ---------------------------------------------------------------- check

/// Slater's assumption (ipm/existence_check.hpp) and cheap diagnostics.
int cmd_check(Args args) {
  const bool json = args.flag("json");
  double max_time = std::numeric_limits<double>::infinity();
  if (auto v = args.take("max-time")) max_time = parse_double("max-time", *v);
  if (!(max_time > 0)) throw UsageError("--max-time must be positive (seconds)");
  const ipm::ExistenceStop stop =
      args.flag("to-optimum") ? ipm::ExistenceStop::AtOptimum : ipm::ExistenceStop::AtCertifiedWitness;
  args.expect_no_more_options();
  if (args.positional.size() != 1) throw UsageError("check takes exactly one FILE");
  const std::string path = args.positional[0];
  const fclib::Problem problem = read_untrusted(path);
  const auto [ex, dg] = std::visit(
      [&](const auto& p) {
        ipm::ExistenceReport report = ipm::check_existence(p, 1e-10, max_time, stop);
        return std::make_pair(std::move(report), ipm::diagnose(p));
      },
      problem);
  const bool global = std::holds_alternative<GlobalProblem>(problem);
  const char* verdict = ex.slater ? "solution-exists" : "not-established";
  if (json) {
    JsonWriter w;
    w.begin_object().field("file", path).field("kind", global ? "global" : "local");
    w.field("x_star", ex.x).field("slater", ex.slater).field("verdict", verdict);
    w.field("witness_norm", ex.witness_norm).field("margin", ex.margin);
    w.field("check_error", ex.solver_error).field("check_status", ipm::check_status(ex));
    w.field("check_iterations", (long long)ex.info.iterations).field("check_program", ex.program);
    if (global) w.field("contact_ratio", dg.contact_ratio);
    w.field(global ? "rank_H" : "rank_W", (long long)dg.rank_H).field("m", (long long)dg.columns_H);
    w.field("lambda_min_W", dg.lambda_min_W).field("lambda_max_W", dg.lambda_max_W);
    w.field("cond_W", dg.cond_W).field("asymmetry_W", dg.asymmetry_W);
    w.end_object();
    std::cout << w.str() << "\n";
    return kExitSolved;
  }
  std::cout << "file=" << path << " x_star=" << fmt(ex.x, "%.6e") << " verdict=" << verdict
            << " witness_norm=" << fmt(ex.witness_norm, "%.6e") << " margin=" << fmt(ex.margin, "%.6e")
            << " check_status=" << ipm::check_status(ex) << " check_program=" << ex.program << "\n";
  std::cout << (global ? "contact_ratio=" + fmt(dg.contact_ratio, "%.4g") + " rank_H=" : "rank_W=")
            << (dg.rank_H >= 0 ? std::to_string(dg.rank_H) : std::string("nan")) << "/" << dg.columns_H
            << " lambda_min_W=" << fmt(dg.lambda_min_W)
            << " lambda_max_W=" << fmt(dg.lambda_max_W) << " cond_W=" << fmt(dg.cond_W)
            << " asymmetry_W=" << fmt(dg.asymmetry_W) << "\n";
  return kExitSolved;
}

// ---------------------------------------------------------------- solvers

int cmd_solvers(Args args) {
  const bool json = args.flag("json");
  args.expect_no_more_options();
  if (json) {
    JsonWriter w;
    w.begin_array();
    for (const auto& e : registry::entries()) {
      json_fields(w.begin_object(), registry::entry_fields(e));
      w.key("settings").begin_array();
      for (const auto& s : e.settings) {
        w.begin_object().field("name", s.name).field("type", registry::to_string(s.type));
        w.field("default", registry::format_value(s.default_value)).field("doc", s.doc);
        if (!s.choices.empty()) {
          w.key("choices").begin_array();
          for (const auto& c : s.choices) w.value(c);
          w.end_array();
        }
        w.end_object();
      }
      w.end_array().end_object();
    }
    w.end_array();
    std::cout << w.str() << "\n";
    return kExitSolved;
  }
  for (const auto& e : registry::entries()) {
    std::cout << e.name << "  [" << e.family << "]  " << e.summary
              << (e.needs_symmetric ? "  (symmetric W)" : "") << "\n";
    for (const auto& s : e.settings) {
      std::cout << "    --" << s.name << " " << registry::to_string(s.type) << " = "
                << registry::format_value(s.default_value);
      if (!s.choices.empty()) {
        std::cout << " {";
        for (std::size_t k = 0; k < s.choices.size(); ++k) std::cout << (k ? "," : "") << s.choices[k];
        std::cout << "}";
      }
      std::cout << "  " << s.doc << "\n";
    }
  }
  if (registry::entries().empty()) std::cout << "(no solver registered)\n";
  return kExitSolved;
}

// ---------------------------------------------------------------- run (main job)

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s) {
    if (c == sep) { if (!cur.empty()) out.push_back(cur); cur.clear(); }
    else cur += c;
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

std::string basename(const std::string& path) {
  const auto slash = path.find_last_of('/');
  std::string b = slash == std::string::npos ? path : path.substr(slash + 1);
  const auto dot = b.rfind(".hdf5");
  return dot == std::string::npos ? b : b.substr(0, dot);
}

/// The main job: every file with every listed solver, as a table.
int cmd_run(Args args) {
  std::vector<std::string> solvers;
  if (auto v = args.take("solvers")) solvers = split(*v, ',');
  else
    for (const auto& e : registry::entries())
      if (e.family == "nsgs") solvers.push_back(e.name);
  if (solvers.empty()) throw UsageError("no solver to run (give --solvers a,b,...)");
  double tol = 1e-8, max_time = 20;
  if (auto v = args.take("tol")) tol = parse_double("tol", *v);
  if (auto v = args.take("max-time")) max_time = parse_double("max-time", *v);
  args.expect_no_more_options();
  if (args.positional.empty()) throw UsageError("run needs at least one FILE");
  for (const auto& s : solvers) registry::find(s);  // fail early on a typo

  std::printf("%-40s %-6s %5s %-14s %-15s %7s %10s %9s\n", "problem", "kind", "nc", "solver",
              "status", "iter", "error", "seconds");
  int solved = 0, runs = 0;
  for (const auto& path : args.positional) {
    fclib::Problem problem;
    try {
      problem = read_untrusted(path);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "fcsolve: skipping %s\n", e.what());
      continue;
    }
    const bool local = std::holds_alternative<LocalProblem>(problem);
    const Index nc = std::visit([](const auto& p) { return p.num_contacts(); }, problem);
    for (const auto& name : solvers) {
      SolveOptions o;
      o.solver = name;
      o.request = registry::make_request(registry::find(name));
      o.request.common.tol = tol;
      o.request.common.max_time = max_time;
      const registry::SolveOutcome out =
          fclib::with_file_context(path, problem, [&] { return solve_file(path, problem, o); });
      ++runs;
      solved += out.info.converged();
      std::printf("%-40s %-6s %5ld %-14s %-15s %7d %10.3e %9.4f\n", basename(path).c_str(),
                  local ? "local" : "global", long(nc), name.c_str(), to_string(out.info.status),
                  out.info.iterations, out.info.error, out.seconds);
    }
  }
  std::printf("%d of %d runs reached tol %.1e\n", solved, runs, tol);
  return kExitSolved;
}

// ---------------------------------------------------------------- generate

int cmd_generate(Args args) {
  fcsolve_cli::GenerateRequest r;
  if (auto v = args.take("contacts")) r.contacts = long(parse_int("contacts", *v));
  if (auto v = args.take("seed")) r.seed = long(parse_int("seed", *v));
  if (auto v = args.take("mu")) r.mu = parse_double("mu", *v);
  if (auto v = args.take("mass-ratio")) {
    r.mass_ratio = parse_double("mass-ratio", *v);
    if (!(r.mass_ratio >= 1)) throw UsageError("generate: --mass-ratio must be in [1, 1e4]");
  }
  if (auto v = args.take("penetration-correction"))
    r.penetration_correction = parse_double("penetration-correction", *v);
  if (auto v = args.take("steps")) {
    r.steps = long(parse_int("steps", *v));
    if (r.steps < 1) throw UsageError("generate: --steps must be in [1, 100000]");
  }
  if (auto v = args.take("out")) r.out = *v;
  if (auto v = args.take("local-out")) r.local_out = *v;
  args.expect_no_more_options();
  if (args.positional.size() != 1) throw UsageError("generate takes exactly one SCENE");
  r.scene = args.positional[0];
  return fcsolve_cli::generate(r);
}

// ---------------------------------------------------------------- bench, report

bool is_file(const std::string& path) { return access(path.c_str(), R_OK) == 0; }

/// This program's own path, so that the campaign runs the same binary.
std::string self_path(const char* argv0) {
  char buf[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n > 0) return std::string(buf, static_cast<std::size_t>(n));
  char* real = realpath(argv0, nullptr);
  std::string out = real ? real : argv0;
  std::free(real);
  return out;
}

/// The campaign package: $FCSOLVE_CAMPAIGN_DIR, else the installed copy
/// (BINDIR/../share/fcsolve/python/fcsolve/campaign), else the source tree
/// this binary was built from.
std::string campaign_dir(const std::string& self) {
  if (const char* env = std::getenv("FCSOLVE_CAMPAIGN_DIR"); env && *env) return env;
  const std::string bindir = self.substr(0, self.find_last_of('/'));
  const std::string candidates[] = {
#ifdef FCSOLVE_CAMPAIGN_RELATIVE_DIR
      bindir + "/" + FCSOLVE_CAMPAIGN_RELATIVE_DIR,
#endif
      fcsolve_cli::campaign_source_dir,
  };
  for (const auto& dir : candidates)
    if (is_file(dir + "/__main__.py")) return dir;
  throw UsageError("the campaign runner (python/fcsolve/campaign) is not installed; set "
                   "FCSOLVE_CAMPAIGN_DIR to its folder");
}

/// `fcsolve bench|report ...` runs the pure-Python campaign runner by path
/// (no `import fcsolve`, so no compiled extension needed) with
/// $FCSOLVE_PYTHON (default /usr/bin/python3, Debian's numpy, scipy, h5py,
/// matplotlib), telling it this binary's path. Replaces this process.
int cmd_campaign(const std::string& command, int argc, char** argv) {
  const std::string self = self_path(argv[0]);
  const std::string script = campaign_dir(self) + "/__main__.py";
  const char* env_python = std::getenv("FCSOLVE_PYTHON");
  const std::string python = env_python && *env_python ? env_python : "/usr/bin/python3";
  setenv("FCSOLVE_CLI", self.c_str(), 1);
  std::vector<std::string> words = {python, script, command};
  for (int k = 2; k < argc; ++k) words.emplace_back(argv[k]);
  std::vector<char*> args;
  for (auto& w : words) args.push_back(w.data());
  args.push_back(nullptr);
  std::cout.flush();
  execv(python.c_str(), args.data());
  std::cerr << "fcsolve: cannot run " << python << " (" << std::strerror(errno)
            << "); set FCSOLVE_PYTHON to a Python with numpy, scipy, h5py and matplotlib\n";
  return kExitInternal;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << kUsage;
    return kExitBadInput;
  }
  const std::string command = argv[1];
  try {
    if (command == "bench" || command == "report") return cmd_campaign(command, argc, argv);
    // Not for the campaign above: its peers run as child processes.
    fcsolve_cli::cap_address_space_at_physical_memory();
    Args args = Args::parse(argc, argv, 2);
    if (command == "info") return cmd_info(args);
    if (command == "solve") return cmd_solve(args);
    if (command == "solvers") return cmd_solvers(args);
    if (command == "check") return cmd_check(args);
    if (command == "run") return cmd_run(args);
    if (command == "error") return cmd_error(args);
    if (command == "generate") return cmd_generate(args);
    if (command == "version" || command == "--version") {
      std::cout << "fcsolve " << FCSOLVE_VERSION_STRING << "\n";
      return kExitSolved;
    }
    if (command == "help" || command == "--help" || command == "-h") {
      std::cout << kUsage;
      return kExitSolved;
    }
    throw UsageError("unknown command '" + command + "'");
  } catch (const IoError& e) {
    std::cerr << "fcsolve: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const InvalidProblem& e) {
    std::cerr << "fcsolve: invalid problem: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const UsageError& e) {
    std::cerr << "fcsolve: " << e.what() << "\n" << kUsage;
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    std::cerr << "fcsolve: out of memory\n";
    return kExitInternal;
  } catch (const std::exception& e) {
    std::cerr << "fcsolve: internal error: " << e.what() << "\n";
    return kExitInternal;
  }
}
