#!/usr/bin/env python3
"""Runs the scaling study of issue 13 item 4 (scripts/scaling.sh drives it).

For every generated problem of OUT/MANIFEST.csv and every solver, one
process per tolerance (1e-4, 1e-6, 1e-8, in that order: a solver that misses
one tolerance is not asked for the next) with --max-time LIMIT. Each row of
OUT/scaling.csv has the process' wall time, the solver's own setup and solve
times, iterations, the FCLIB error, status and the peak resident memory
(os.wait4's ru_maxrss of that one process). `overrun` = wall - max_time when
the run stopped on its time limit: the --max-time contract is that it stays
within 10 % + one iteration.

Local-form solvers on an elastic scene beyond --max-dense-contacts are not
run: W = H^T M^-1 H is dense there (9 nc^2 doubles: 7 GB at nc = 10^4);
their rows say so (status `skipped-dense-W`).
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile
import time

TOLERANCES = (1e-4, 1e-6, 1e-8)
LOCAL_FORM = {"nsgs", "nsn-ac"}  # solve FC/II: an FC/I file is reduced first
FIELDS = ["scene", "nc", "n", "solver", "tol", "max_time", "status", "converged", "iterations",
          "error", "wall_seconds", "setup_seconds", "solve_seconds", "peak_rss_mb", "overrun",
          "file", "message"]


def run_one(cli, path, solver, tol, limit):
    """One solve in its own process: (json dict or None, wall s, peak RSS MB, stderr text).

    The child is reaped with os.wait4, whose rusage is that process' own
    (RUSAGE_CHILDREN would be the maximum over every child so far)."""
    cmd = [cli, "solve", path, "--solver", solver, "--tol", repr(tol), "--max-time", str(limit),
           "--json"]
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    hard_stop = 2 * limit + 60  # far beyond the contract: one broken run cannot eat the study
    with tempfile.TemporaryFile() as out_f, tempfile.TemporaryFile() as err_f:
        start = time.perf_counter()
        proc = subprocess.Popen(cmd, stdout=out_f, stderr=err_f, env=env)
        killed = False
        while True:
            pid, status, usage = os.wait4(proc.pid, 0 if killed else os.WNOHANG)
            if pid == proc.pid:
                break
            if time.perf_counter() - start > hard_stop:
                proc.kill()
                killed = True
            time.sleep(0.01)
        wall = time.perf_counter() - start
        proc.returncode = os.waitstatus_to_exitcode(status)
        out_f.seek(0)
        err_f.seek(0)
        out = out_f.read().decode(errors="replace")
        err = err_f.read().decode(errors="replace")
    if killed:
        err = "killed after %.0f s (2 max_time + 60)\n" % hard_stop + err
    result = None
    for line in out.splitlines():
        if line.strip().startswith("{"):
            try:
                result = json.loads(line)
            except json.JSONDecodeError:
                pass
    return result, wall, usage.ru_maxrss / 1024.0, err  # Linux: ru_maxrss in kB


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", help="directory with MANIFEST.csv (scripts/scaling.sh writes it)")
    ap.add_argument("--cli", required=True)
    ap.add_argument("--solvers", default="nsgs,nsn-ac,nsn-ac-global,nipm,aclm-newton,auto")
    ap.add_argument("--time-limit", type=float, default=60.0, help="--max-time of every run (s)")
    ap.add_argument("--max-dense-contacts", type=int, default=1500)
    args = ap.parse_args()

    with open(os.path.join(args.out, "MANIFEST.csv")) as f:
        problems = [row for row in csv.DictReader(f)]
    rows = []
    result_path = os.path.join(args.out, "scaling.csv")
    with open(result_path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=FIELDS)
        writer.writeheader()
        for prob in problems:
            nc, elastic = int(prob["nc"]), prob["scene"].startswith("fem")
            for solver in args.solvers.split(","):
                for tol in TOLERANCES:
                    row = {"scene": prob["scene"], "nc": nc, "n": prob["n"], "solver": solver,
                           "tol": tol, "max_time": args.time_limit, "file": prob["file"]}
                    if elastic and solver in LOCAL_FORM and nc > args.max_dense_contacts:
                        row.update(status="skipped-dense-W", converged=False,
                                   message="W = H^T M^-1 H is dense for an elastic body")
                        writer.writerow(row)
                        rows.append(row)
                        break
                    res, wall, rss, err = run_one(args.cli, os.path.join(args.out, prob["file"]),
                                                  solver, tol, args.time_limit)
                    row.update(wall_seconds="%.3f" % wall,
                               peak_rss_mb="" if rss is None else "%.0f" % rss)
                    if res is None:
                        row.update(status="crashed", converged=False, message=err.strip()[-300:])
                    else:
                        row.update(status=res["status"], converged=res["converged"],
                                   iterations=res["iterations"], error="%.3e" % res["error"],
                                   setup_seconds="%.6f" % res["setup_seconds"],
                                   solve_seconds="%.6f" % res["solve_seconds"],
                                   message=res["message"][:300])
                        if res["status"] == "time-limit":
                            row["overrun"] = "%.3f" % (wall - args.time_limit)
                    writer.writerow(row)
                    f.flush()
                    rows.append(row)
                    print("%-12s nc=%-6d %-14s tol=%.0e %-15s %8.2f s %6s MB" %
                          (prob["scene"], nc, solver, tol, row["status"], wall,
                           row["peak_rss_mb"]), flush=True)
                    if not row["converged"]:
                        break  # a tighter tolerance will not be reached either
    print("wrote", result_path)


if __name__ == "__main__":
    sys.exit(main())
