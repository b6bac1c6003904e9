#!/usr/bin/env python3
"""`auto` against every single fcsolve solver on a set of FCLIB files.

Each (problem, solver) is one `fcsolve solve FILE --solver S --json` process
with --tol and --max-time (solves under 1 s repeated --repeat times, the
fastest kept); a run counts as solved when the FCLIB error of
the solution it wrote, recomputed by shared/tools/fcref.py (numpy/scipy,
independent of fcsolve), is <= tol (problems with bilateral constraints,
which fcref does not handle, fall back on fcsolve's own re-check). Results
are appended as JSON lines to --out, so an interrupted run resumes where it
stopped; --summary prints solved counts, total time against the virtual
best (sum over problems of the fastest solver's time) and the worst
per-problem ratio.

    /usr/bin/python3 bench/auto_vs_single.py --cli build/fcsolve \\
        --out auto.jsonl ../shared/data/fclib/*/*.hdf5
    /usr/bin/python3 bench/auto_vs_single.py --out auto.jsonl --summary
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TOOLS = ROOT.parent / "shared" / "tools"

# Likely winners first: an interrupted campaign still covers them.
DEFAULT_SOLVERS = [
    "auto", "nsgs", "nsn-ac", "nsn-fb", "nsn-jm", "nsn-nm", "nsn-ac-hybrid", "nsn-ac-global",
    "nipm", "aclm-newton", "nsn-fb-global", "nsn-jm-global", "nsn-nm-global", "psor", "nsgs-ac",
    "nsgs-fb", "nsgs-hybrid", "nsgs-exact", "nsgs-proj", "nsgs-proj-iter", "aclm-fp",
    "ipm-socqp", "vi-eg", "vi-fp",
]


def independent_error(problem_path, solution_path):
    if not (TOOLS / "fcref.py").is_file():
        return None
    sys.path.insert(0, str(TOOLS))
    import fcref
    import h5py
    import numpy as np
    prob = fcref.load(str(problem_path))
    if "G" in prob:
        return None
    with h5py.File(solution_path, "r") as f:
        r = np.asarray(f["solution/r"])
        v = np.asarray(f["solution/v"]) if "solution/v" in f else None
    return float(fcref.error(prob, r, v))


def run_one(cli, path, solver, tol, max_time):
    with tempfile.TemporaryDirectory() as tmp:
        sol = Path(tmp) / "sol.hdf5"
        cmd = [cli, "solve", str(path), "--solver", solver, "--tol", str(tol),
               "--max-time", str(max_time), "--json", "--out", str(sol)]
        try:
            p = subprocess.run(cmd, capture_output=True, text=True, timeout=3 * max_time + 30,
                               env=dict(os.environ, OPENBLAS_NUM_THREADS="1"))
        except subprocess.TimeoutExpired:
            return dict(status="killed", seconds=None, error=None, ref_error=None)
        if p.returncode not in (0, 1):
            return dict(status=f"exit-{p.returncode}", seconds=None, error=None, ref_error=None,
                        stderr=p.stderr[-300:])
        out = json.loads(p.stdout)
        ref = independent_error(path, sol) if sol.exists() else None
        rec = dict(status=out["status"], seconds=out["seconds"], error=out["error"],
                   iterations=out["iterations"], ref_error=ref)
        if "stages" in out:
            rec["stages"] = [(s["solver"], round(s["seconds"], 4), s["iterations"], s["error"])
                             for s in out["stages"]]
        return rec


def solved(rec, tol):
    e = rec.get("ref_error")
    if e is None:
        e = rec.get("error") if rec.get("status") == "converged" else None
    return e is not None and e <= tol and rec.get("seconds") is not None


def summary(records, tol, auto="auto"):
    by = {}
    for r in records:
        by.setdefault(r["problem"], {})[r["solver"]] = r
    solvers = sorted({r["solver"] for r in records})
    problems = sorted(by)
    best = {}
    for prob, runs in by.items():
        times = [r["seconds"] for s, r in runs.items() if s != auto and solved(r, tol)]
        best[prob] = min(times) if times else None
    print(f"{len(problems)} problems, tol {tol:g}")
    print(f"{'solver':16s} {'solved':>7s} {'runs':>5s} {'time on VB-solved':>18s} {'x VB':>6s} "
          f"{'worst ratio':>12s}  worst problem")
    vb_total = sum(t for t in best.values() if t is not None)
    rows = []
    for s in solvers:
        runs = [by[p][s] for p in problems if s in by[p]]
        n_solved = sum(solved(r, tol) for r in runs)
        total, worst, worst_p, complete = 0.0, 0.0, "", True
        for p in problems:
            if best[p] is None:
                continue
            r = by[p].get(s)
            if r is None or not solved(r, tol):
                complete = False
                continue
            total += r["seconds"]
            ratio = r["seconds"] / max(best[p], 1e-6)
            if ratio > worst:
                worst, worst_p = ratio, p
        rows.append((s, n_solved, len(runs), total, complete, worst, worst_p))
    for s, n, k, total, complete, worst, wp in sorted(rows, key=lambda x: (-x[1], x[3])):
        t = f"{total:.3f}" + ("" if complete else "*")
        print(f"{s:16s} {n:7d} {k:5d} {t:>18s} {total / vb_total:6.2f} {worst:12.2f}  {Path(wp).stem}")
    n_vb = sum(t is not None for t in best.values())
    print(f"virtual best (single solvers): solves {n_vb}, total {vb_total:.3f} s "
          "(* : the solver misses some problems the virtual best solves)")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="*")
    ap.add_argument("--cli", default=str(ROOT / "build" / "fcsolve"))
    ap.add_argument("--solvers", default=",".join(DEFAULT_SOLVERS))
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--max-time", type=float, default=20)
    ap.add_argument("--out", required=True)
    ap.add_argument("--repeat", type=int, default=3, help="runs of solves under 1 s (fastest kept)")
    ap.add_argument("--summary", action="store_true")
    ap.add_argument("--redo", default="", help="solvers whose records are replaced (e.g. auto)")
    a = ap.parse_args()
    out = Path(a.out)
    records = [json.loads(l) for l in out.read_text().splitlines() if l.strip()] if out.exists() else []
    if a.summary:
        summary(records, a.tol)
        return
    redo = set(filter(None, a.redo.split(",")))
    if redo:
        records = [r for r in records if r["solver"] not in redo]
        out.write_text("".join(json.dumps(r) + "\n" for r in records))
    done = {(r["problem"], r["solver"]) for r in records}
    # Problem by problem, every solver in turn: a busy spell of a shared
    # machine hits auto and the single solvers alike.
    for f in a.files:
        for solver in a.solvers.split(","):
            name = Path(f).name
            if (name, solver) in done:
                continue
            rec = run_one(a.cli, f, solver, a.tol, a.max_time)
            # short solves: best of --repeat runs (noise of a shared machine)
            for _ in range(a.repeat - 1):
                if rec.get("seconds") is None or rec["seconds"] >= 1:
                    break
                again = run_one(a.cli, f, solver, a.tol, a.max_time)
                if again.get("seconds") is not None and again["seconds"] < rec["seconds"] \
                        and again["status"] == rec["status"]:
                    rec = again
            rec.update(problem=name, solver=solver)
            with out.open("a") as fh:
                fh.write(json.dumps(rec) + "\n")
            print(f"{solver:14s} {name:45s} {rec['status']:14s} {rec['seconds']} {rec.get('ref_error')}",
                  flush=True)


if __name__ == "__main__":
    main()
