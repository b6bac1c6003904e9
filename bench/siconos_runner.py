#!/usr/bin/python3
"""Solve ONE FCLIB problem with a named Siconos 4.4 solver (siconos.numerics).

    /usr/bin/python3 bench/siconos_runner.py PROBLEM.hdf5 --solver NSGS \\
        [--tol 1e-8] [--max-time 20] [--max-iter 1000000] [--out SOLUTION.hdf5]

Writes r, u (and v for global problems) to /solution of --out and prints one
JSON line: solver, status, iterations, seconds (measured around the Siconos
calls only: reformulation and solve, not file reading nor error checks),
siconos_residual (Siconos' own error) and error (the FCLIB error, computed
by fclib_arrays.py, for information; compare_siconos.py recomputes it).

The problem is built from arrays read with h5py: this Siconos build has no
FCLIB reader in its Python module. Global problems are solved by the
reduction Siconos itself provides (globalFrictionContact_reformulation_
FrictionContact, what its *_WR solvers do) followed by the local solver, and
v is recovered by globalFrictionContact_computeGlobalVelocity; solvers
marked "global" in SOLVERS call gfc3d_driver on the global problem instead.

Iterative local solvers run in chunks of growing iteration counts, warm
started, so that the time budget can be honoured (a C call cannot be
interrupted); the result is the same as one long run. Siconos' own stopping
test scales the residual differently from FCLIB (by max(||q||, ||r||, ||u||)
in fc3d_compute_error), so when Siconos reports convergence but the FCLIB
error is above --tol, its tolerance is tightened and the run continues: the
time measured is the time Siconos needs to reach --tol as FCLIB measures it.
"""
import argparse
import json
import os
import sys
import time
import warnings

import numpy as np
import scipy.sparse as sp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fclib_arrays  # noqa: E402


def _nsgs_full_error(sn, so):
    # full error every sweep: Siconos' default (light error, full at the end)
    # keeps sweeping long after the FCLIB error is met
    so.iparam[sn.SICONOS_FRICTION_3D_IPARAM_ERROR_EVALUATION] = \
        sn.SICONOS_FRICTION_3D_NSGS_ERROR_EVALUATION_FULL


def _nsgs_shuffled(sn, so):
    _nsgs_full_error(sn, so)
    so.iparam[sn.SICONOS_FRICTION_3D_NSGS_SHUFFLE] = sn.SICONOS_FRICTION_3D_NSGS_SHUFFLE_TRUE_EACH_LOOP


def _psor(sn, so):
    _nsgs_full_error(sn, so)
    so.iparam[sn.SICONOS_FRICTION_3D_NSGS_RELAXATION] = sn.SICONOS_FRICTION_3D_NSGS_RELAXATION_TRUE
    so.dparam[sn.SICONOS_FRICTION_3D_NSGS_RELAXATION_VALUE] = OPTIONS["omega"]


OPTIONS = {"omega": 1.0}  # set from the command line


def _nsn_jean_moreau(sn, so):
    so.iparam[sn.SICONOS_FRICTION_3D_NSN_FORMULATION] = \
        sn.SICONOS_FRICTION_3D_NSN_FORMULATION_JEANMOREAU_GENERATED


# name -> how to run it. "local": a fc3d solver id (global problems are
# reduced first); "global": a gfc3d solver id run on the global problem.
# "configure" adjusts the SolverOptions; "chunked": iterative, may be run in
# pieces. Other issues add their rows here (Newton: NSN-*, IPM: IPM).
SOLVERS = {
    "NSGS": dict(local="SICONOS_FRICTION_3D_NSGS", configure=_nsgs_full_error, chunked=True),
    "NSGS-SHUFFLE": dict(local="SICONOS_FRICTION_3D_NSGS", configure=_nsgs_shuffled, chunked=True),
    "PSOR": dict(local="SICONOS_FRICTION_3D_NSGS", configure=_psor, chunked=True),
    "NSN-AC": dict(local="SICONOS_FRICTION_3D_NSN_AC", chunked=True),
    "NSN-FB": dict(local="SICONOS_FRICTION_3D_NSN_FB", chunked=True),
    "NSN-NM": dict(local="SICONOS_FRICTION_3D_NSN_NM", chunked=True),
    "NSN-JM": dict(local="SICONOS_FRICTION_3D_NSN_AC", configure=_nsn_jean_moreau, chunked=True),
    "IPM": dict(global_="SICONOS_GLOBAL_FRICTION_3D_IPM", chunked=False),
    # gfc3d solvers on the global problem: NSGS on Siconos' own reduction
    # (then v), and Alart-Curnier Newton in (v, r).
    "GNSGS-WR": dict(global_="SICONOS_GLOBAL_FRICTION_3D_NSGS_WR", chunked=False),
    "GNSN-AC": dict(global_="SICONOS_GLOBAL_FRICTION_3D_NSN_AC", chunked=False),
}


def _int64_csc(A):
    A = sp.csc_matrix(A)
    A.indices = A.indices.astype(np.int64)
    A.indptr = A.indptr.astype(np.int64)
    return A


class Budget:
    def __init__(self, max_time, max_iter):
        self.max_time, self.max_iter = max_time, max_iter
        self.seconds, self.iterations = 0.0, 0

    def timed(self, fn, *args):
        t = time.perf_counter()
        out = fn(*args)
        self.seconds += time.perf_counter() - t
        return out


def run_local(sn, spec, fcp, m, tol, budget, meter, v_of):
    """Runs a fc3d solver on `fcp` within the budget; returns r, u, status, residual."""
    r, u = np.zeros(m), np.zeros(m)
    solver_tol, chunk, residual = tol, 100, float("nan")
    while True:
        so = sn.SolverOptions(getattr(sn, spec["local"]))
        if spec.get("configure"):
            spec["configure"](sn, so)
        left = budget.max_iter - budget.iterations
        so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = min(chunk, left) if spec["chunked"] else left
        so.dparam[sn.SICONOS_DPARAM_TOL] = solver_tol
        info = budget.timed(sn.fc3d_driver, fcp, r, u, so)
        budget.iterations += int(so.iparam[sn.SICONOS_IPARAM_ITER_DONE])
        residual = float(so.dparam[sn.SICONOS_DPARAM_RESIDU])
        if not np.all(np.isfinite(r)):
            return r, u, "nan", residual
        error = meter.error(r, v_of(r))
        if error <= tol:
            return r, u, "converged", residual
        if budget.seconds >= budget.max_time:
            return r, u, "timeout", residual
        if budget.iterations >= budget.max_iter or not spec["chunked"]:
            return r, u, "max-iterations" if info != 0 else "stalled", residual
        if info == 0:  # converged by Siconos' scaling, not by FCLIB's: tighten
            if solver_tol < 1e-16:
                return r, u, "stalled", residual
            solver_tol *= 0.5 * tol / error
        else:  # grow the chunks, but keep the next one within the time left
            per_iteration = budget.seconds / max(budget.iterations, 1)
            left = (budget.max_time - budget.seconds) / max(per_iteration, 1e-9)
            chunk = int(max(10, min(2 * chunk, 1.1 * left)))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("problem")
    ap.add_argument("--solver", default="NSGS", choices=sorted(SOLVERS))
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--max-time", type=float, default=20.0)
    ap.add_argument("--max-iter", type=int, default=10**7)
    ap.add_argument("--out")
    ap.add_argument("--omega", type=float, default=1.0, help="relaxation of PSOR")
    args = ap.parse_args()
    OPTIONS["omega"] = args.omega
    result = dict(solver=args.solver, file=args.problem)
    try:
        import siconos.numerics as sn
    except ImportError as e:
        result.update(status="unavailable", message=f"siconos.numerics cannot be imported: {e}")
        print(json.dumps(result))
        return 3
    warnings.filterwarnings("ignore")  # int32 -> int64 conversion notices
    spec = SOLVERS[args.solver]
    P = fclib_arrays.read_problem(args.problem)
    if P["d"] != 3:
        result.update(status="unsupported", message="only 3D problems are compared")
        print(json.dumps(result))
        return 2
    if P["kind"] == "local" and "local" not in spec:
        result.update(status="unsupported", message=f"{args.solver} is a global (gfc3d) solver")
        print(json.dumps(result))
        return 2
    meter = fclib_arrays.ErrorMeter(P)
    budget = Budget(args.max_time, args.max_iter)
    m, nc = P["mu"].size * 3, P["mu"].size
    v = None
    if P["kind"] == "local" and "local" not in spec:
        result.update(status="unsupported", message=f"{args.solver} solves global problems only")
        print(json.dumps(result))
        return 2
    if P["kind"] == "local":
        fcp = sn.FrictionContactProblem(3, _int64_csc(P["W"]), P["q"].copy(), P["mu"].copy())
        r, u, status, residual = run_local(sn, spec, fcp, m, args.tol, budget, meter, lambda r: None)
    else:
        gfc = sn.GlobalFrictionContactProblem()
        gfc.dimension, gfc.numberOfContacts = 3, nc
        # Siconos: M v = q + H r, u = H^T v + b  (FCLIB: f, w)
        gfc.M, gfc.H = _int64_csc(P["M"]), _int64_csc(P["H"])
        gfc.q, gfc.b, gfc.mu = P["f"].copy(), P["w"].copy(), P["mu"].copy()
        n = P["f"].size
        if "local" in spec:
            fcp = budget.timed(sn.globalFrictionContact_reformulation_FrictionContact, gfc)

            def v_of(r):
                v = np.zeros(n)
                sn.globalFrictionContact_computeGlobalVelocity(gfc, r, v)
                return v

            r, u, status, residual = run_local(sn, spec, fcp, m, args.tol, budget, meter, v_of)
            v = budget.timed(v_of, r)
        else:
            so = sn.SolverOptions(getattr(sn, spec["global_"]))
            so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = min(args.max_iter, 2**31 - 1)
            so.dparam[sn.SICONOS_DPARAM_TOL] = args.tol
            r, u, v = np.zeros(m), np.zeros(m), np.zeros(n)
            info = budget.timed(sn.gfc3d_driver, gfc, r, u, v, so)
            budget.iterations = int(so.iparam[sn.SICONOS_IPARAM_ITER_DONE])
            residual = float(so.dparam[sn.SICONOS_DPARAM_RESIDU])
            status = "converged" if meter.error(r, v) <= args.tol else (
                "max-iterations" if info != 0 else "stalled")
    error = meter.error(r, v)
    if args.out:
        fclib_arrays.write_solution(args.out, r, u, v)
    result.update(status=status, iterations=budget.iterations, seconds=budget.seconds,
                  siconos_residual=residual, error=error, tol=args.tol)
    print(json.dumps(result))
    return 0 if status == "converged" else 1


if __name__ == "__main__":
    sys.exit(main())
