#!/usr/bin/python3
"""Runs one Siconos 4.4 solver on one FCLIB problem, like `fcsolve solve`.

    /usr/bin/python3 siconos_runner.py FILE --solver nsgs --tol 1e-8 --out SOL.hdf5 --json
    /usr/bin/python3 siconos_runner.py --list          # the solvers, as JSON

Prints one JSON line (solver, status, iterations, error, seconds, ...) and
writes /solution/{r, u[, v]} to SOL. Exit codes as fcsolve's: 0 converged by
Siconos' own test, 1 not, 2 bad input or solver not available for the
problem, 3 Siconos not importable. Local problems go to fc3d_driver, global
ones to gfc3d_driver (problem objects built from the arrays; this Siconos has
no FCLIB reader in its Python module).

`error` here is Siconos' own residual (its own scaling); the campaign
recomputes the FCLIB error from SOL, and that is what counts. Siconos has no
time limit: the campaign's wall-clock limit stops it. `seconds` is the
driver call alone. Run with the Python that has siconos (/usr/bin/python3),
by path: it imports its neighbour fclib_error.py as a plain module.
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

import fclib_error  # the campaign's reader, beside this file

# name -> (local solver id, global solver id), as SICONOS_* constant suffixes;
# None: Siconos has no such solver for that kind of problem.
SOLVERS = {
    "nsgs": ("FRICTION_3D_NSGS", "GLOBAL_FRICTION_3D_NSGS_WR"),
    "nsn-ac": ("FRICTION_3D_NSN_AC", "GLOBAL_FRICTION_3D_NSN_AC"),
    "nsn-fb": ("FRICTION_3D_NSN_FB", None),
    "vi-eg": ("FRICTION_3D_VI_EG", "GLOBAL_FRICTION_3D_VI_EG"),
    "vi-fp": ("FRICTION_3D_VI_FPP", "GLOBAL_FRICTION_3D_VI_FPP"),
    "admm": ("FRICTION_3D_ADMM", "GLOBAL_FRICTION_3D_ADMM"),
    "prox": ("FRICTION_3D_PROX", "GLOBAL_FRICTION_3D_PROX_WR"),
    "aclm": ("FRICTION_3D_ACLMFP", "GLOBAL_FRICTION_3D_ACLMFP"),
    "tresca": ("FRICTION_3D_TFP", "GLOBAL_FRICTION_3D_TFP_WR"),
    "ipm": (None, "GLOBAL_FRICTION_3D_IPM"),
}
# Time is the campaign's budget, so iterations are nearly unbounded by default.
DEFAULT_MAX_ITER = 100000


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


def solve(sn, problem, name, tol, max_iter):
    """(info, r, u, v or None, iterations, own error, seconds) of one solve."""
    local_id, global_id = SOLVERS[name]
    solver_id = local_id if problem.kind == "local" else global_id
    if solver_id is None:
        raise ValueError(f"Siconos has no {problem.kind} solver for '{name}'")
    options = sn.SolverOptions(getattr(sn, "SICONOS_" + solver_id))
    options.iparam[sn.SICONOS_IPARAM_MAX_ITER] = max_iter
    options.dparam[sn.SICONOS_DPARAM_TOL] = tol
    if name == "nsgs" and problem.kind == "local":
        # Full error every sweep, as fcsolve's nsgs checks it: Siconos'
        # default (a light error, the full one at the end) keeps sweeping long
        # after the FCLIB error is met, which would make it look slower.
        options.iparam[sn.SICONOS_FRICTION_3D_IPARAM_ERROR_EVALUATION] = \
            sn.SICONOS_FRICTION_3D_NSGS_ERROR_EVALUATION_FULL
    m = problem.m
    r, u = np.zeros(m), np.zeros(m)
    if problem.kind == "local":
        sp_problem = sn.FrictionContactProblem(problem.d, _csc64(problem.W), problem.q, problem.mu)
        start = time.perf_counter()
        with _StdoutToStderr():
            info = sn.fc3d_driver(sp_problem, r, u, options)
        v = None
    else:
        if problem.G is not None:
            raise ValueError("bilateral constraints (G, b) are not passed to Siconos here")
        sp_problem = sn.GlobalFrictionContactProblem()
        sp_problem.dimension = problem.d
        sp_problem.numberOfContacts = problem.nc
        # Siconos: M v = q + H r, u = H^T v + b  (FCLIB: f, w)
        sp_problem.M, sp_problem.H = _csc64(problem.M), _csc64(problem.H)
        sp_problem.q, sp_problem.b = problem.f.copy(), problem.w.copy()
        sp_problem.mu = problem.mu.copy()
        v = np.zeros(problem.n)
        start = time.perf_counter()
        with _StdoutToStderr():
            info = sn.gfc3d_driver(sp_problem, r, u, v, options)
    seconds = time.perf_counter() - start
    return (info, r, u, v, int(options.iparam[sn.SICONOS_IPARAM_ITER_DONE]),
            float(options.dparam[sn.SICONOS_DPARAM_RESIDU]), seconds)


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
    ap.add_argument("--max-iter", type=int, default=DEFAULT_MAX_ITER)
    ap.add_argument("--max-time", type=float, help="accepted, not enforced (no time limit in Siconos)")
    ap.add_argument("--out")
    ap.add_argument("--json", action="store_true", help="accepted: output is always JSON")
    a = ap.parse_args(argv)
    warnings.simplefilter("ignore")  # Siconos' conversion warnings
    try:
        import siconos.numerics as sn
    except ImportError as e:
        print(f"siconos_runner: siconos is not importable by {sys.executable}: {e}", file=sys.stderr)
        return 3
    if a.list:
        print(json.dumps([dict(name=k, local=v[0] is not None, global_native=v[1] is not None)
                          for k, v in SOLVERS.items()]))
        return 0
    if not a.file or a.solver not in SOLVERS:
        print(f"siconos_runner: give FILE and --solver in {sorted(SOLVERS)}", file=sys.stderr)
        return 2
    try:
        problem = fclib_error.load_problem(a.file)
        info, r, u, v, iterations, own_error, seconds = solve(sn, problem, a.solver, a.tol, a.max_iter)
    except (OSError, ValueError, KeyError) as e:
        print(f"siconos_runner: {a.file}: {e}", file=sys.stderr)
        return 2
    if a.out:
        write_solution(a.out, r, u, v)
    status = status_of(info, r, iterations, a.max_iter)
    print(json.dumps(dict(file=a.file, kind=problem.kind, solver="siconos:" + a.solver,
                          status=status, converged=status == "converged", iterations=iterations,
                          error=own_error if np.isfinite(own_error) else None, tol=a.tol,
                          seconds=seconds, setup_seconds=0.0, solve_seconds=seconds,
                          message=f"siconos info={info}", out=a.out)))
    return 0 if status == "converged" else 1


if __name__ == "__main__":
    sys.exit(main())
