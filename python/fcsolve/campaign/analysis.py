"""Numbers behind the report, computed from typed CSV rows (results.load_results).

Performance profiles (Dolan & More 2002, "Benchmarking optimization software
with performance profiles", Math. Prog. 91(2); Acary 2025 (talk), eqs.
(21)-(22); docs/references.md):
for a measure t_{p,s} (time, iterations) of solver s on problem p,

    tau_{p,s} = t_{p,s} / min_s t_{p,s}       (infinite when s did not solve p)
    rho_s(tau) = |{p : tau_{p,s} <= tau}| / |P|

where "solved" means the recomputed error <= tol. P is every problem of the
campaign at that tolerance, including the ones no solver solved (they keep
every rho_s below 1, which is the truth about the solver set); a solver with
no row for a problem (kind not supported) has not solved it.
"""
import math

import numpy as np

# Below these, measures are noise: a 1e-7 s run is not 100x faster than 1e-5 s.
MEASURE_FLOOR = {"seconds": 1e-6, "iterations": 1}


def ordered(values):
    """Unique values in first-seen order."""
    return list(dict.fromkeys(values))


def tolerances(rows):
    return sorted({r["tol"] for r in rows}, reverse=True)


def solver_names(rows):
    """fcsolve's solvers first, then the peers (PEER:NAME), each in CSV order."""
    names = ordered(r["solver"] for r in rows)
    return [n for n in names if ":" not in n] + [n for n in names if ":" in n]


def measure_table(rows, measure, tol, solvers=None):
    """(problems, solvers, T) with T[p, s] the measure when solved, inf otherwise.

    `solvers` restricts the columns (a family view); the problems stay every
    problem of the campaign at tol."""
    at_tol = [r for r in rows if r["tol"] == tol]
    problems = ordered(r["problem"] for r in at_tol)
    solvers = list(solvers) if solvers is not None else solver_names(at_tol)
    at_tol = [r for r in at_tol if r["solver"] in set(solvers)]
    pi = {p: k for k, p in enumerate(problems)}
    si = {s: k for k, s in enumerate(solvers)}
    T = np.full((len(problems), len(solvers)), np.inf)
    floor = MEASURE_FLOOR.get(measure, 0)
    for r in at_tol:
        value = r.get(measure)
        if r["solved"] and value is not None and math.isfinite(value):
            T[pi[r["problem"]], si[r["solver"]]] = max(float(value), floor)
    return problems, solvers, T


def performance_ratios(T):
    """tau[p, s] = T[p, s] / min_s T[p, s]; inf where unsolved or nobody solved p."""
    best = T.min(axis=1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore"):
        tau = T / best
    tau[~np.isfinite(T)] = np.inf
    return tau


def profile(tau, taus):
    """rho[s, k]: fraction of problems with tau[:, s] <= taus[k]."""
    taus = np.asarray(taus, dtype=float)
    n = tau.shape[0]
    if n == 0:
        return np.zeros((tau.shape[1], taus.size))
    return (tau.T[:, :, None] <= taus[None, None, :]).sum(axis=1) / n


def profile_axis(tau, points=400):
    """tau values for plotting: 1 to a bit past the largest finite ratio (log scale)."""
    finite = tau[np.isfinite(tau)]
    top = max(2.0, float(finite.max()) * 1.5) if finite.size else 2.0
    return np.unique(np.concatenate([np.geomspace(1.0, top, points), np.sort(finite)]))


def geometric_mean(values):
    values = [v for v in values if v is not None and math.isfinite(v) and v > 0]
    return float(math.exp(sum(math.log(v) for v in values) / len(values))) if values else None


def summary(rows):
    """Per solver and tolerance: runs, solved fraction, median and geometric-mean
    time on solved runs, and the count of each failure class."""
    out = []
    for s in solver_names(rows):
        for tol in tolerances(rows):
            rs = [r for r in rows if r["solver"] == s and r["tol"] == tol]
            if not rs:
                continue
            times = [max(r["seconds"], MEASURE_FLOOR["seconds"]) for r in rs
                     if r["solved"] and r["seconds"] is not None]
            failures = {}
            for r in rs:
                failures[r["failure"]] = failures.get(r["failure"], 0) + 1
            out.append(dict(solver=s, tol=tol, runs=len(rs), solved=len(times),
                            solved_fraction=len(times) / len(rs),
                            median_seconds=float(np.median(times)) if times else None,
                            geomean_seconds=geometric_mean(times), failures=failures))
    return out


def by_family(rows, tol):
    """{family: {solver: (solved, problems)}} at one tolerance; `problems`
    counts every problem of the family, run by that solver or not."""
    at = [r for r in rows if r["tol"] == tol]
    family_of = {r["problem"]: r.get("family") or "" for r in at}
    sizes = {}
    for p, f in family_of.items():
        sizes[f] = sizes.get(f, 0) + 1
    out = {f: {s: [0, n] for s in solver_names(at)} for f, n in sorted(sizes.items())}
    for r in at:
        if r["solved"]:
            out[family_of[r["problem"]]][r["solver"]][0] += 1
    return {f: {s: tuple(v) for s, v in d.items()} for f, d in out.items()}


def work_precision(rows, solvers=None):
    """Time to reach each accuracy, per solver: {solver: [(tol, time, fraction)]}
    (every solver of the campaign, or those in `solvers`, in that order).

    `time` is the geometric mean over every problem of the campaign of the
    solver's time, an unsolved (or unsupported) problem counted at the time
    limit, so that the curves of different solvers cover the same problems
    and a tighter tolerance can only cost more (a mean over solved runs only
    would drop the hard problems and get faster). `fraction` is the fraction
    of the problems solved.
    """
    out = {}
    for tol in tolerances(rows):
        at = [r for r in rows if r["tol"] == tol]
        limits = [r["time_limit"] for r in at if r.get("time_limit")]
        default_limit = max(limits) if limits else max(
            (r["seconds"] or 0 for r in at), default=1.0)
        by_key = {(r["problem"], r["solver"]): r for r in at}
        problems = ordered(r["problem"] for r in at)
        for s in (solver_names(at) if solvers is None else
                  [s for s in solvers if any(r["solver"] == s for r in at)]):
            times, solved_count = [], 0
            for p in problems:
                r = by_key.get((p, s))
                if r is not None and r["solved"] and r["seconds"] is not None:
                    times.append(max(r["seconds"], MEASURE_FLOOR["seconds"]))
                    solved_count += 1
                else:
                    times.append((r or {}).get("time_limit") or default_limit)
            out.setdefault(s, []).append(
                (tol, geometric_mean(times), solved_count / len(problems)))
    return out


# ---------------------------------------------------------------- family view
# One line per solver family (its best member), auto, and the peers reduced
# the same way: the all-solver charts of a 30-solver campaign cannot be read.

AUTO_FAMILY = "auto"
MAX_FAMILY_LINES = 8


def family_of_solver(name, families=None):
    """The solver's family: from `families` ({solver: family}, what campaign.json
    recorded), else the peer for PEER:NAME, else the name itself."""
    if families and families.get(name):
        return families[name]
    return name.split(":", 1)[0] if ":" in name else name


def solved_and_time(rows, solver, tol):
    """(problems solved, total seconds on the solved ones) of one solver at tol."""
    count, total = 0, 0.0
    for r in rows:
        if r["solver"] == solver and r["tol"] == tol and r["solved"]:
            count += 1
            total += max(r["seconds"] or 0.0, MEASURE_FLOOR["seconds"])
    return count, total


def best_members(rows, families=None):
    """{family: best member}, families in first-seen order.

    The rule: at the tightest tolerance of the campaign, the member that solved
    the most problems wins; ties go to the smaller total time on the problems it
    solved, then to the name (so the choice never depends on row order). Solved
    means the recomputed error within tol, as everywhere in the report. A peer
    (family = the peer, e.g. siconos) is reduced to its best solver the same way.
    """
    if not rows:
        return {}
    tight = min(tolerances(rows))
    members = {}
    for s in solver_names(rows):
        members.setdefault(family_of_solver(s, families), []).append(s)
    best = {}
    for family, names in members.items():
        def key(s):
            count, total = solved_and_time(rows, s, tight)
            return (-count, total, s)
        best[family] = min(names, key=key)
    return best


def family_lines(rows, families=None, max_lines=MAX_FAMILY_LINES, always=(AUTO_FAMILY,)):
    """The lines of the family view: ([(family, solver)], [left-out families]).

    One line per family (best_members). With more families than max_lines, the
    families in `always` (auto) are kept and the others ranked by problems
    solved at the tightest tolerance (then total time, then name); the best
    fill the remaining places, the rest are returned as left out. The kept
    lines come `always` first, then in that ranking.
    """
    best = best_members(rows, families)
    if not best:
        return [], []
    tight = min(tolerances(rows))

    def rank(family):
        count, total = solved_and_time(rows, best[family], tight)
        return (-count, total, family)

    kept = [f for f in always if f in best]
    others = sorted((f for f in best if f not in kept), key=rank)
    room = max(max_lines - len(kept), 0)
    return [(f, best[f]) for f in kept + others[:room]], others[room:]
