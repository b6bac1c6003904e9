#!/usr/bin/python3
"""Runs one Siconos 4.4 solver on one FCLIB problem, like `fcsolve solve`.

    /usr/bin/python3 siconos_runner.py FILE --solver nsgs --tol 1e-8 --max-time 20 \\
        [--max-iter N] [--omega 1.0] [--repeat N] --out SOL.hdf5 --json
    /usr/bin/python3 siconos_runner.py --list          # the solvers, as JSON

Prints one JSON line (solver, status, iterations, error, fclib_error, seconds,
...) and writes /solution/{r, u[, v]} to SOL. Exit codes as fcsolve's: 0
converged by Siconos' own test, 1 not, 2 bad input or solver not available
for the problem, 3 Siconos not importable. The problem objects are built from
arrays read by the neighbour fclib_error.py (this Siconos has no FCLIB reader
in its Python module). Used by the campaign (`fcsolve bench --solvers
siconos:...`) and by bench/compare_siconos.py.

Iterative solvers ("chunked" below) run in chunks of growing iteration
counts, warm started, so that --max-time is honoured (a C call cannot be
interrupted; the result is that of one long run). Siconos' own stopping test
scales its residual differently from FCLIB (fc3d_compute_error divides by
max(||q||, ||r||, ||u||)), so when Siconos reports convergence but the FCLIB
error (fclib_error.py) is above --tol, its tolerance is tightened and the run
goes on: `seconds` is then the time Siconos needs to reach --tol as FCLIB
measures it. Global problems are solved either by Siconos' own reduction
(globalFrictionContact_reformulation_FrictionContact, what its *_WR solvers
do, then the local solver, then v by globalFrictionContact_computeGlobalVelocity;
as fcsolve's local solvers do) or by a native gfc3d solver (ipm, gnsgs-wr,
gnsn-ac, ...), in one call. Other solvers run once, up to --max-iter; the
campaign's wall-clock limit stops them.

`error` is Siconos' own residual (its own scaling), `fclib_error` the FCLIB
one, for information: the campaign and compare_siconos.py recompute the error
from SOL, and that is what counts. `seconds` covers the Siconos calls only
(reformulation, solver, global velocity), not file reading nor error checks.
Run with the Python that has siconos (/usr/bin/python3), by path: it imports
its neighbour fclib_error.py as a plain module.
"""
import argparse
import ctypes
import json
import os
import sys
import time
import warnings

import h5py
import numpy as np
import scipy.sparse as sp

import fclib_error  # the campaign's reader and error measure, beside this file

REDUCE = "reduce"  # a global problem: Siconos' reduction, then the local solver
OPTIONS = {"omega": 1.0}  # --omega, read by _psor


def _nsgs_full_error(sn, so):
    # A tuned set-up, not Siconos' default: the full error every sweep (as
    # fcsolve's nsgs checks it). Stock NSGS (`nsgs`) evaluates a light error
    # each sweep and the full one at the end, as its users run it; compare
    # with `nsgs` and show this one only beside it.
    so.iparam[sn.SICONOS_FRICTION_3D_IPARAM_ERROR_EVALUATION] = \
        sn.SICONOS_FRICTION_3D_NSGS_ERROR_EVALUATION_FULL


def _nsgs_shuffled(sn, so):
    so.iparam[sn.SICONOS_FRICTION_3D_NSGS_SHUFFLE] = sn.SICONOS_FRICTION_3D_NSGS_SHUFFLE_TRUE_EACH_LOOP


def _psor(sn, so):
    so.iparam[sn.SICONOS_FRICTION_3D_NSGS_RELAXATION] = sn.SICONOS_FRICTION_3D_NSGS_RELAXATION_TRUE
    so.dparam[sn.SICONOS_FRICTION_3D_NSGS_RELAXATION_VALUE] = OPTIONS["omega"]


def _nsn_jean_moreau(sn, so):
    so.iparam[sn.SICONOS_FRICTION_3D_NSN_FORMULATION] = \
        sn.SICONOS_FRICTION_3D_NSN_FORMULATION_JEANMOREAU_GENERATED


def _spec(local=None, global_=None, configure=None, chunked=False):
    """local: fc3d solver id; global_: gfc3d solver id or REDUCE (SICONOS_*
    suffixes; None: no such solver for that kind of problem)."""
    return dict(local=local, global_=global_, configure=configure, chunked=chunked)


SOLVERS = {
    "nsgs": _spec("FRICTION_3D_NSGS", REDUCE, chunked=True),  # stock settings
    "nsgs-full-error": _spec("FRICTION_3D_NSGS", REDUCE, _nsgs_full_error, chunked=True),
    "nsgs-shuffle": _spec("FRICTION_3D_NSGS", REDUCE, _nsgs_shuffled, chunked=True),
    "psor": _spec("FRICTION_3D_NSGS", REDUCE, _psor, chunked=True),
    "nsn-ac": _spec("FRICTION_3D_NSN_AC", REDUCE, chunked=True),
    "nsn-fb": _spec("FRICTION_3D_NSN_FB", REDUCE, chunked=True),
    "nsn-nm": _spec("FRICTION_3D_NSN_NM", REDUCE, chunked=True),
    "nsn-jm": _spec("FRICTION_3D_NSN_AC", REDUCE, _nsn_jean_moreau, chunked=True),
    "vi-eg": _spec("FRICTION_3D_VI_EG", "GLOBAL_FRICTION_3D_VI_EG"),
    "vi-fp": _spec("FRICTION_3D_VI_FPP", "GLOBAL_FRICTION_3D_VI_FPP"),
    "admm": _spec("FRICTION_3D_ADMM", "GLOBAL_FRICTION_3D_ADMM"),
    "prox": _spec("FRICTION_3D_PROX", "GLOBAL_FRICTION_3D_PROX_WR"),
    "aclm": _spec("FRICTION_3D_ACLMFP", "GLOBAL_FRICTION_3D_ACLMFP"),
    "tresca": _spec("FRICTION_3D_TFP", "GLOBAL_FRICTION_3D_TFP_WR"),
    "dsfp": _spec("FRICTION_3D_DSFP", "GLOBAL_FRICTION_3D_DSFP_WR"),
    "pfp": _spec("FRICTION_3D_PFP", REDUCE),
    # native gfc3d solvers, global problems only
    "ipm": _spec(None, "GLOBAL_FRICTION_3D_IPM"),
    "gnsgs-wr": _spec(None, "GLOBAL_FRICTION_3D_NSGS_WR"),
    "gnsn-ac": _spec(None, "GLOBAL_FRICTION_3D_NSN_AC"),
    "gadmm": _spec(None, "GLOBAL_FRICTION_3D_ADMM"),
}
# Time is the budget, so iterations are (nearly) unbounded by default: the
# chunked solvers stop at --max-time, the others at this count or when the
# campaign's wall-clock limit kills them.
DEFAULT_MAX_ITER = 100000
CHUNKED_DEFAULT_MAX_ITER = 2**31 - 1


def _csc64(A):
    """CSC with 64-bit indices, the layout Siconos takes without conversion."""
    A = sp.csc_matrix(A)
    return sp.csc_matrix((A.data, A.indices.astype(np.int64), A.indptr.astype(np.int64)),
                         shape=A.shape)


class _StdoutToStderr:
    """Sends the C library's prints (IPM tables) to stderr, keeping stdout for JSON."""

    def __enter__(self):
        sys.stdout.flush()
        self.saved = os.dup(1)
        os.dup2(2, 1)

    def __exit__(self, *exc):
        ctypes.CDLL(None).fflush(None)
        os.dup2(self.saved, 1)
        os.close(self.saved)


class Budget:
    """Seconds and iterations spent in Siconos calls, against the limits."""

    def __init__(self, max_time, max_iter):
        self.max_time = float("inf") if max_time is None else max_time
        self.max_iter = min(max_iter, 2**31 - 1)  # iparam is a C int
        self.seconds, self.iterations = 0.0, 0

    def timed(self, fn, *args):
        start = time.perf_counter()
        with _StdoutToStderr():
            out = fn(*args)
        self.seconds += time.perf_counter() - start
        return out


def _options(sn, solver_id, configure, max_iter, tol):
    so = sn.SolverOptions(getattr(sn, "SICONOS_" + solver_id))
    if configure:
        configure(sn, so)
    so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = max_iter
    so.dparam[sn.SICONOS_DPARAM_TOL] = tol
    return so


def run_local(sn, spec, fcp, m, tol, budget, fclib_error_of):
    """Runs a fc3d solver on `fcp` within the budget: (info, r, u, status, own residual)."""
    r, u = np.zeros(m), np.zeros(m)
    solver_tol, chunk = tol, 100
    while True:
        left = budget.max_iter - budget.iterations
        so = _options(sn, spec["local"], spec["configure"],
                      min(chunk, left) if spec["chunked"] else left, solver_tol)
        info = budget.timed(sn.fc3d_driver, fcp, r, u, so)
        done = int(so.iparam[sn.SICONOS_IPARAM_ITER_DONE])
        budget.iterations += done
        residual = float(so.dparam[sn.SICONOS_DPARAM_RESIDU])
        if not np.all(np.isfinite(r)):
            return info, r, u, "nan", residual
        if not spec["chunked"]:
            return info, r, u, None, residual  # Siconos' own claim decides
        error = fclib_error_of(r)
        if error <= tol:
            return info, r, u, "converged", residual
        if budget.seconds >= budget.max_time:
            return info, r, u, "timeout", residual
        if budget.iterations >= budget.max_iter:
            return info, r, u, "max-iterations", residual
        if info == 0:  # converged by Siconos' scaling, not by FCLIB's: tighten
            if solver_tol < 1e-16:  # Siconos' claim stands; the recomputed error refutes it
                return info, r, u, "converged", residual
            solver_tol *= 0.5 * tol / error
        elif done == 0:
            return info, r, u, "stalled", residual
        else:  # grow the chunks, keeping the next one within the time left
            per_iteration = budget.seconds / max(budget.iterations, 1)
            left_iterations = (budget.max_time - budget.seconds) / max(per_iteration, 1e-9)
            chunk = int(max(10, min(2 * chunk, 1.1 * left_iterations)))


def _global_problem(sn, problem):
    if problem.G is not None:
        raise ValueError("bilateral constraints (G, b) are not passed to Siconos here")
    gfc = sn.GlobalFrictionContactProblem()
    gfc.dimension, gfc.numberOfContacts = problem.d, problem.nc
    # Siconos: M v = q + H r, u = H^T v + b  (FCLIB: f, w)
    gfc.M, gfc.H = _csc64(problem.M), _csc64(problem.H)
    gfc.q, gfc.b, gfc.mu = problem.f.copy(), problem.w.copy(), problem.mu.copy()
    return gfc


def solve(sn, problem, name, tol, max_iter, max_time=None):
    """(info, r, u, v or None, status or None, iterations, own residual, seconds)
    of one run; status None: Siconos' own claim decides."""
    spec = SOLVERS[name]
    if problem.d != 3:
        raise ValueError("Siconos' fc3d/gfc3d solvers take 3D problems only")
    route = spec["local"] if problem.kind == "local" else spec["global_"]
    if route is None:
        raise ValueError(f"Siconos has no {problem.kind} solver for '{name}'")
    budget = Budget(max_time, max_iter)
    m, v = problem.m, None
    if problem.kind == "local":
        fcp = sn.FrictionContactProblem(problem.d, _csc64(problem.W), problem.q.copy(),
                                        problem.mu.copy())
        info, r, u, status, residual = run_local(
            sn, spec, fcp, m, tol, budget, lambda r: fclib_error.error(problem, r))
    elif route == REDUCE:
        gfc = _global_problem(sn, problem)
        fcp = budget.timed(sn.globalFrictionContact_reformulation_FrictionContact, gfc)

        def v_of(r):
            v = np.zeros(problem.n)
            sn.globalFrictionContact_computeGlobalVelocity(gfc, r, v)
            return v

        info, r, u, status, residual = run_local(
            sn, spec, fcp, m, tol, budget, lambda r: fclib_error.error(problem, r, v_of(r)))
        v = budget.timed(v_of, r)
    else:
        gfc = _global_problem(sn, problem)
        so = _options(sn, route, None, budget.max_iter, tol)
        r, u, v = np.zeros(m), np.zeros(m), np.zeros(problem.n)
        info = budget.timed(sn.gfc3d_driver, gfc, r, u, v, so)
        budget.iterations = int(so.iparam[sn.SICONOS_IPARAM_ITER_DONE])
        residual, status = float(so.dparam[sn.SICONOS_DPARAM_RESIDU]), None
    return info, r, u, v, status, budget.iterations, residual, budget.seconds


def write_solution(path, r, u, v):
    with h5py.File(path, "w") as f:
        g = f.create_group("solution")
        for name, x in (("r", r), ("u", u), ("v", v)):
            if x is not None:
                g.create_dataset(name, data=x)


def status_of(info, r, iterations, max_iter):
    if not np.all(np.isfinite(r)):
        return "nan"
    if info == 0:
        return "converged"
    return "max-iterations" if iterations >= max_iter else "stalled"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("file", nargs="?")
    ap.add_argument("--list", action="store_true", help="print the solvers as JSON")
    ap.add_argument("--solver", default="nsgs")
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--max-iter", type=int,
                    help=f"default: unbounded for the chunked solvers, else {DEFAULT_MAX_ITER}")
    ap.add_argument("--max-time", type=float,
                    help="seconds; honoured by the chunked solvers (nsgs, psor, nsn-*), "
                         "the others run to --max-iter")
    ap.add_argument("--omega", type=float, default=1.0, help="relaxation of psor")
    ap.add_argument("--repeat", type=int, default=1,
                    help="solve N times in this process and report the fastest (a hot loop for "
                         "sub-millisecond problems; the solvers are deterministic)")
    ap.add_argument("--out")
    ap.add_argument("--json", action="store_true", help="accepted: output is always JSON")
    a = ap.parse_args(argv)
    OPTIONS["omega"] = a.omega
    warnings.simplefilter("ignore")  # Siconos' conversion warnings
    try:
        import siconos.numerics as sn
    except ImportError as e:
        print(f"siconos_runner: siconos is not importable by {sys.executable}: {e}", file=sys.stderr)
        return 3
    if a.list:
        # global_native: can solve FC/I (by Siconos' reduction or a gfc3d solver)
        print(json.dumps([dict(name=k, local=s["local"] is not None,
                               global_native=s["global_"] is not None,
                               global_by=None if s["global_"] is None else
                               "reduction" if s["global_"] == REDUCE else "gfc3d",
                               chunked=s["chunked"])
                          for k, s in SOLVERS.items()]))
        return 0
    if not a.file or a.solver not in SOLVERS:
        print(f"siconos_runner: give FILE and --solver in {sorted(SOLVERS)}", file=sys.stderr)
        return 2
    if a.max_iter is None:
        a.max_iter = CHUNKED_DEFAULT_MAX_ITER if SOLVERS[a.solver]["chunked"] else DEFAULT_MAX_ITER
    try:
        problem = fclib_error.load_problem(a.file)
        info, r, u, v, status, iterations, own_error, seconds = solve(
            sn, problem, a.solver, a.tol, a.max_iter, a.max_time)
        for _ in range(max(a.repeat, 1) - 1):
            seconds = min(seconds, solve(sn, problem, a.solver, a.tol, a.max_iter, a.max_time)[-1])
    except (OSError, ValueError, KeyError) as e:
        print(f"siconos_runner: {a.file}: {e}", file=sys.stderr)
        return 2
    if a.out:
        write_solution(a.out, r, u, v)
    status = status or status_of(info, r, iterations, a.max_iter)
    fclib = fclib_error.error(problem, r, v)
    finite = lambda x: x if np.isfinite(x) else None  # noqa: E731
    print(json.dumps(dict(file=a.file, kind=problem.kind, solver="siconos:" + a.solver,
                          status=status, converged=status == "converged", iterations=iterations,
                          error=finite(own_error), fclib_error=finite(fclib), tol=a.tol,
                          seconds=seconds, setup_seconds=0.0, solve_seconds=seconds,
                          message=f"siconos info={info}", out=a.out)))
    return 0 if status == "converged" else 1


if __name__ == "__main__":
    sys.exit(main())
