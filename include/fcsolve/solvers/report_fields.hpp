// A solve outcome, the stages of a staged solve and a catalogue entry as
// ordered fields (core/report_fields.hpp): what `fcsolve solve` and
// `fcsolve solvers --json` print and what Python's Result.stages and
// fcsolve.solvers() return.
#pragma once

#include <fcsolve/core/report_fields.hpp>
#include <fcsolve/core/status.hpp>
#include <fcsolve/solvers/registry.hpp>

namespace fcsolve {
namespace registry {

/// solver, status, iterations, error, tol, seconds (all forms); converged,
/// the setup/solve split and the message (the message in the key=value line
/// only when there is one).
inline Fields outcome_fields(const SolveOutcome& out, double tol) {
  return {Field::text("solver", out.solver),
          Field::text("status", to_string(out.info.status)),
          Field::flag("converged", out.info.converged(), ShownStructured),
          Field::integer("iterations", out.info.iterations),
          Field::real("error", out.info.error, "%.3e"),
          Field::real("tol", tol, "%.1e"),
          Field::real("seconds", out.seconds, "%.4g"),
          Field::real("setup_seconds", out.info.setup_seconds, "%.4g", ShownStructured),
          Field::real("solve_seconds", out.info.solve_seconds, "%.4g", ShownStructured),
          Field::text("message", out.info.message, /*quoted_in_text=*/true,
                      out.info.message.empty() ? ShownStructured : ShownEverywhere)};
}

/// One stage of a staged solve (`auto`).
inline Fields stage_fields(const StageReport& st) {
  return {Field::text("stage", st.name),           Field::text("solver", st.solver),
          Field::real("seconds", st.seconds),       Field::integer("iterations", st.iterations),
          Field::real("error", st.error),           Field::text("status", st.status),
          Field::text("why", st.why)};
}

/// A catalogue entry without its settings (whose defaults each front end
/// writes in its own types: text for the CLI, Python values for Python).
inline Fields entry_fields(const SolverEntry& e) {
  return {Field::text("name", e.name),
          Field::text("family", e.family),
          Field::text("summary", e.summary),
          Field::flag("needs_symmetric", e.needs_symmetric),
          Field::integer("default_max_iter", e.default_max_iter),
          Field::flag("local", bool(e.solve_local)),
          Field::flag("global_native", e.solves_global_natively())};
}

}  // namespace registry
}  // namespace fcsolve
