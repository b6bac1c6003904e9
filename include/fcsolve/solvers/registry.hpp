// The run-time solver catalogue: every solver family registers named entries
// (e.g. "nsgs", "nsn-ac", "nipm") with typed settings, so the CLI, the Python
// module and the benchmark tools reach every solver by name without knowing
// its template parameters.
//
// registry::solve() is the one door they all use. It validates the problem,
// solves a global problem natively or by reduction (W = H^T M^-1 H) with the
// recovery of v, works on the symmetric part of W for solvers that need
// symmetry, and recomputes the FCLIB error of the returned solution against
// the data as given: a run is "converged" only if that error is within tol.
#pragma once

#include <fcsolve/problem/error.hpp>
#include <fcsolve/core/solver_settings.hpp>
#include <fcsolve/core/timer.hpp>
#include <fcsolve/linalg/default_backend.hpp>
#include <fcsolve/problem/reduction.hpp>
#include <fcsolve/problem/symmetry.hpp>
#include <fcsolve/problem/validate.hpp>
#include <fcsolve/solvers/settings_schema.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace fcsolve {
namespace registry {

struct SolveRequest {
  SolverSettings common;   ///< tol, max_iter, max_time, history, callback
  SettingValues settings;  ///< the entry's own knobs (defaults unless set)
  Vector r0;               ///< warm start for r (empty: solver's default start)
  Vector v0;               ///< warm start for v (global-native solvers)
  /// ||H^T M^-1 f + w|| of the FC/I problem, if the caller knows it (an
  /// earlier solve of the same problem: SolveOutcome::reduced_q_norm); < 0:
  /// unknown. Saves registry::solve a factorisation of M for the error scale.
  double reduced_q_norm = -1;
};

/// One stage of a staged solver (`auto`): which entry ran, for how long,
/// what it reached and why the plan ran it.
struct StageReport {
  std::string name;    ///< the stage's role: "nsgs", "newton"
  std::string solver;  ///< the catalogue entry that ran
  double seconds = 0;
  int iterations = 0;
  double error = 0;    ///< FCLIB error of the stage's returned r
  std::string status;  ///< to_string(Status) of the stage
  std::string why;     ///< why the plan ran this stage
};

struct SolveOutcome {
  Vector r, u, v, lambda;  ///< v, lambda only for global problems
  SolverInfo info;         ///< status, iterations, error, timings, history
  double seconds = 0;      ///< wall time of the whole call (incl. reduction)
  std::string solver;
  std::vector<StageReport> stages;  ///< staged solvers only (`auto`)
  /// FC/I: ||H^T M^-1 f + w||, the scale of the FCLIB error, as the entry
  /// found it (a reduction, or a native solver that factorised M) and as
  /// registry::solve used it; < 0: unknown (local problems, or a native entry
  /// that does not pass it on; the registry then computes it).
  double reduced_q_norm = -1;
};

using LocalSolveFunction =
    std::function<SolveOutcome(const LocalProblemView&, const SolveRequest&)>;
using GlobalSolveFunction =
    std::function<SolveOutcome(const GlobalProblemView&, const SolveRequest&)>;

struct SolverEntry {
  SolverEntry() = default;
  /// The entry's identity; its family sets settings, budget and solve functions.
  SolverEntry(std::string name_, std::string family_, std::string summary_)
      : name(std::move(name_)), family(std::move(family_)), summary(std::move(summary_)) {}

  std::string name;     ///< CLI name, e.g. "nsgs-ac"
  std::string family;   ///< "nsgs", "newton", "ipm", ...
  std::string summary;  ///< one line for `fcsolve solvers`
  std::vector<SettingSpec> settings;
  /// true: the method assumes a symmetric W; on unsymmetric data it is run on
  /// (W + W^T)/2 and its error is reported against W as given.
  bool needs_symmetric = false;
  /// Typical iteration budget when the caller gives none (max_iter <= 0).
  int default_max_iter = 1000;
  LocalSolveFunction solve_local;    ///< FC/II; may be empty if global-only
  /// FC/I natively (in (v, r), W never formed); empty: the registry reduces
  /// FC/I to FC/II and runs solve_local. A native solver whose formulation
  /// has no bilateral constraints (G, b) reduces those problems itself, with
  /// solve_by_reduction() below.
  GlobalSolveFunction solve_global;

  /// Whether FC/I problems reach a native global solver (the flag the
  /// registry and `fcsolve solvers` go by).
  bool solves_global_natively() const { return bool(solve_global); }
};

/// The catalogue's time rule: a request's max_time counts from the start of
/// the call, its set-up included (a reduction to FC/II, compute()'s
/// factorisations), so that a caller asking for T seconds has the answer
/// within T and at most one iteration, whatever the set-up costs (issue 13:
/// admm-global asked for 2.5 s on an elastic block of 10^4 contacts
/// returned after 4.7-5.2 s, 2.2 s of them factorising M before its clock
/// started). Returns what is left of `max_time` after `spent` seconds; when
/// nothing is, a sliver, so that the solver still returns its start's error
/// after at most one iteration.
inline double time_left(double max_time, double spent) {
  constexpr double kLeastTimeLeft = 1e-9;  // > 0: every solver rejects max_time <= 0
  return std::isfinite(max_time) ? std::max(max_time - spent, kLeastTimeLeft) : max_time;
}

/// `req` with what is left of its max_time after the time on `since`: what
/// a solve run after a set-up of its own (a reduction) is given.
inline SolveRequest within_time(const SolveRequest& req, const Stopwatch& since) {
  SolveRequest within = req;
  within.common.max_time = time_left(req.common.max_time, since.seconds());
  return within;
}

/// The starting reactions of a solve: the request's warm start, else zero.
inline Vector initial_reactions(const SolveRequest& req, Index size) {
  return req.r0.size() ? req.r0 : Vector(Vector::Zero(size));
}

/// The seconds a reduction to FC/II may take (solve_by_reduction): what is
/// left of the request's max_time on `clock` (infinite, and no clock read,
/// without a limit), and the request, whose start a reduction that runs out
/// of time returns.
struct ReductionTime {
  ReductionTime(const SolveRequest& request, const Stopwatch& clock)
      : req(request),
        seconds_left(std::isfinite(request.common.max_time) ? time_left(request.common.max_time, clock.seconds())
                                                            : request.common.max_time) {}
  const SolveRequest& req;
  double seconds_left;
};

/// FC/I through FC/II: reduces p (W = H^T M^-1 H, q; problem/reduction.hpp),
/// runs `solve_reduced(LocalProblemView)` and recovers v (and lambda when p
/// has bilateral constraints). The outcome keeps the error scale
/// ||H^T M^-1 f + w|| (`reduced_q_norm`).
/// The one place the registry and the native entries reduce. W is formed
/// within `timed`'s seconds or not at all (GlobalReduction::compute): the
/// outcome is then the request's starting point, no iteration, TimeLimit
/// (issue 13: nsgs asked for 5 s on an elastic block of 4000 contacts given
/// as FC/I ran 176 s, 175 of them forming W, 13 GB).
template <class Backend = DefaultBackend, class SolveReduced>
SolveOutcome solve_by_reduction(const GlobalProblemView& p, const ReductionTime& timed,
                                SolveReduced&& solve_reduced) {
  GlobalReduction<Backend> reduction(p, /*form_W=*/true, timed.seconds_left);
  const double reduce_seconds = reduction.seconds();
  SolveOutcome out;
  if (reduction.formed_W()) {
    out = solve_reduced(LocalProblemView(reduction.local()));
  } else {
    out.r = initial_reactions(timed.req, p.size());
    out.info.status = Status::TimeLimit;
    out.info.message = "max_time spent forming W = H^T M^-1 H (the reduction to FC/II): no iteration run";
  }
  out.v = reduction.velocity(out.r);
  if (p.has_bilateral()) out.lambda = reduction.multipliers(out.r);
  out.info.setup_seconds += reduce_seconds;
  out.reduced_q_norm = reduction.free_velocity_norm();
  return out;
}

/// solve_by_reduction() for a native FC/I entry that cannot take (G, b):
/// `solve_reduced(reduced, within)` gets `req` with what the reduction left
/// of its max_time (within_time); the message says the reduced form was
/// solved.
template <class SolveReduced>
SolveOutcome solve_bilateral_by_reduction(const GlobalProblemView& p, const SolveRequest& req,
                                          SolveReduced&& solve_reduced) {
  const Stopwatch clock;
  SolveOutcome out = solve_by_reduction(p, ReductionTime(req, clock), [&](const LocalProblemView& reduced) {
    if (!std::isfinite(req.common.max_time)) return solve_reduced(reduced, req);
    return solve_reduced(reduced, within_time(req, clock));
  });
  out.info.message = "bilateral constraints: reduced to FC/II" +
                     (out.info.message.empty() ? std::string() : "; " + out.info.message);
  return out;
}

/// solver.compute(p), its time charged to the solver's max_time (time_left);
/// no clock is read when there is no limit.
template <class Solver, class View>
void compute_within_time(Solver& solver, const View& p) {
  double& max_time = solver.settings().max_time;
  if (!std::isfinite(max_time)) {
    solver.compute(p);
    return;
  }
  const Stopwatch setup;
  solver.compute(p);
  max_time = time_left(max_time, setup.seconds());
}

/// Runs a solver of the contract (core/solver_contract.hpp), its settings
/// already set: compute(p) within the request's time, then solve from the
/// request's warm start. On FC/I (a global-native solver) v comes out with
/// the error scale the solver computed, so that the registry need not
/// factorise M again.
template <class Solver, class View>
SolveOutcome compute_and_solve(Solver& solver, const View& p, const SolveRequest& req) {
  compute_within_time(solver, p);
  SolveOutcome out;
  out.r = initial_reactions(req, p.size());
  if constexpr (std::is_same_v<View, GlobalProblemView>) {
    out.v.resize(p.num_dofs());
    out.info = solver.solve(out.r, out.v);
    out.reduced_q_norm = solver.free_velocity_norm();
  } else {
    out.u.resize(p.size());
    out.info = solver.solve(out.r, out.u);
  }
  return out;
}

/// A request with the entry's default settings.
inline SolveRequest make_request(const SolverEntry& e) {
  SolveRequest req;
  req.settings = SettingValues(e.settings);
  req.common.max_iter = e.default_max_iter;
  return req;
}

namespace detail {

/// Downgrades a claimed convergence that the independent error contradicts.
inline void enforce_tolerance(SolveOutcome& out, double error, double tol) {
  out.info.error = error;
  if (!std::isfinite(error)) {
    out.info.status = Status::NumericalError;
    out.info.message += (out.info.message.empty() ? "" : "; ") + std::string("non-finite error");
  } else if (out.info.status == Status::Converged && !(error <= tol)) {
    out.info.status = Status::Stalled;
    out.info.message += (out.info.message.empty() ? "" : "; ") +
                        std::string("solver claimed convergence but the recomputed error exceeds tol");
  }
}

inline void check_warm_start(const Vector& x, Index size, const char* name) {
  if (x.size() != 0 && x.size() != size)
    throw InvalidProblem(name, "warm start has " + std::to_string(x.size()) +
                                   " entries, expected " + std::to_string(size));
  if (x.size() != 0 && !x.allFinite()) throw InvalidProblem(name, "warm start is not finite");
}

/// The common request, checked once for every front end (CLI, Python, C++):
/// tol finite and > 0, max_iter in [1, kMaxIterations], max_time > 0
/// (+inf: no limit). Front ends pass what they parsed, before narrowing.
inline constexpr long long kMaxIterations = 1000000000;

inline std::string shown(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

inline void check_common(double tol, long long max_iter, double max_time) {
  if (!(tol > 0) || !std::isfinite(tol))
    throw UsageError("tol must be a finite positive number, got " + shown(tol));
  if (max_iter < 1 || max_iter > kMaxIterations)
    throw UsageError("max_iter must be in [1, 1e9], got " + std::to_string(max_iter));
  if (!(max_time > 0))
    throw UsageError("max_time must be positive (seconds; inf: no limit), got " + shown(max_time));
}

/// A solver entry that returns a solution of the wrong size is a bug in
/// that entry: say so instead of multiplying mismatched sizes.
inline void check_returned(const Vector& x, Index size, const std::string& solver, const char* name) {
  if (x.size() != size)
    throw std::logic_error("solver '" + solver + "' returned " + name + " with " +
                           std::to_string(x.size()) + " entries, expected " + std::to_string(size));
}

/// registry::solve on FC/II after its checks of the request and problem:
/// runs the entry (on the symmetric part of W when it needs one) and judges
/// its r by the recomputed FCLIB error; out.seconds counts from `clock`.
inline SolveOutcome run_checked(const LocalProblemView& p, const SolverEntry& e, const SolveRequest& req,
                                const Stopwatch& clock) {
  check_warm_start(req.r0, p.size(), "r0");
  if (!e.solve_local) throw UsageError("solver '" + e.name + "' does not solve local problems");
  SolveOutcome out;
  std::string note;
  if (e.needs_symmetric && relative_asymmetry(p.W) > kSymmetryRoundoff) {
    LocalProblem sym;
    sym.d = p.d;
    sym.W = symmetric_part(p.W);
    sym.q = p.q;
    sym.mu = p.mu;
    out = e.solve_local(sym, req);
    note = "solved on the symmetric part of W; error against W as given";
  } else {
    out = e.solve_local(p, req);
  }
  check_returned(out.r, p.size(), e.name, "r");
  out.u = p.W * out.r + p.q;
  enforce_tolerance(out, local_error_report(p, out.r, out.u).error, req.common.tol);
  if (!note.empty()) out.info.message = note + (out.info.message.empty() ? "" : "; " + out.info.message);
  out.solver = e.name;
  out.seconds = clock.seconds();
  return out;
}

}  // namespace detail

/// Solves FC/II with the named solver.
inline SolveOutcome solve(const LocalProblemView& p, const SolverEntry& e, const SolveRequest& req) {
  Stopwatch clock;
  detail::check_common(req.common.tol, req.common.max_iter, req.common.max_time);
  validate(p);
  return detail::run_checked(p, e, req, clock);
}

/// solve() without validate(p), for a staged entry (`auto`) whose problem
/// registry::solve already validated: its stages would otherwise check the
/// same data again each (O(nnz), and a few thousand instructions of strings
/// on a problem of a few contacts). Every other check, the run and the
/// recomputed error are solve()'s.
inline SolveOutcome solve_validated(const LocalProblemView& p, const SolverEntry& e,
                                    const SolveRequest& req) {
  detail::check_common(req.common.tol, req.common.max_iter, req.common.max_time);
  return detail::run_checked(p, e, req, Stopwatch());
}

namespace detail {

/// registry::solve on FC/I after check_common and validate(p): natively if
/// the entry can, else by reduction to FC/II and recovery of v (and lambda).
template <class Backend>
SolveOutcome run_checked(const GlobalProblemView& p, const SolverEntry& e, const SolveRequest& req,
                         const Stopwatch& clock) {
  check_warm_start(req.r0, p.size(), "r0");
  check_warm_start(req.v0, p.num_dofs(), "v0");
  SolveOutcome out;
  if (e.solves_global_natively()) {
    out = e.solve_global(p, req);
  } else {
    if (!e.solve_local) throw UsageError("solver '" + e.name + "' has no entry point");
    out = solve_by_reduction<Backend>(p, ReductionTime(req, clock), [&](const LocalProblemView& reduced) {
      Stopwatch inner;
      validate(reduced);
      if (!std::isfinite(req.common.max_time)) return run_checked(reduced, e, req, inner);
      return run_checked(reduced, e, within_time(req, clock), inner);  // the reduction's time counts
    });
  }
  check_returned(out.r, p.size(), e.name, "r");
  check_returned(out.v, p.num_dofs(), e.name, "v");
  // The error scale: what the entry or the caller already computed, else one
  // factorisation of M (GlobalReduction without W) here.
  if (out.reduced_q_norm < 0) out.reduced_q_norm = req.reduced_q_norm;
  if (out.reduced_q_norm < 0)
    out.reduced_q_norm = GlobalReduction<Backend>(p, /*form_W=*/false).free_velocity_norm();
  out.u = p.H.transpose() * out.v + p.w;
  const GlobalErrorReport rep = global_error_report(p, out.reduced_q_norm, out.r, out.v, out.lambda);
  enforce_tolerance(out, rep.error, req.common.tol);
  out.solver = e.name;
  out.seconds = clock.seconds();
  return out;
}

}  // namespace detail

/// Solves FC/I with the named solver: natively if the entry can, else by
/// reduction to FC/II and recovery of v (and lambda).
template <class Backend = DefaultBackend>
SolveOutcome solve(const GlobalProblemView& p, const SolverEntry& e, const SolveRequest& req) {
  Stopwatch clock;
  detail::check_common(req.common.tol, req.common.max_iter, req.common.max_time);
  validate(p);
  return detail::run_checked<Backend>(p, e, req, clock);
}

/// solve() on FC/I without validate(p): see the FC/II solve_validated().
template <class Backend = DefaultBackend>
SolveOutcome solve_validated(const GlobalProblemView& p, const SolverEntry& e, const SolveRequest& req) {
  detail::check_common(req.common.tol, req.common.max_iter, req.common.max_time);
  return detail::run_checked<Backend>(p, e, req, Stopwatch());
}

}  // namespace registry
}  // namespace fcsolve
