#!/usr/bin/env python3
"""Side by side: fcsolve's Newton solvers against Siconos 4.4's NSN solvers.

    /usr/bin/python3 bench/newton_vs_siconos.py [--fcsolve build/fcsolve]
        [--data ../shared/data/fclib] [--tol 1e-8] [--max-time 20]
        [--pairs nsn-ac:NSN_AC,nsn-fb:NSN_FB,...] [--json out.json] [FILES...]

Every run gets the same tolerance and time limit; every returned solution is
measured with the same independent error (shared/tools/fcref.py). Siconos
runs in a child process per problem (killed at the time limit + 5 s), on the
local problem as given, and on global problems both natively (gfc3d NSN_AC)
and on the reduction W = H^T M^-1 H, q = H^T M^-1 f + w.
fcsolve runs through its CLI (`fcsolve solve FILE --solver NAME --json`),
whose error is fcref's by construction and is re-checked here.
Prints per problem and pair: status, time, iterations, fcref error, and the
time ratio fcsolve / Siconos; then the solved counts and median ratios.
Siconos absent: a clear message, fcsolve columns only.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DEFAULT_DATA = os.path.join(ROOT, "..", "shared", "data", "fclib")
FCREF_DIRS = [os.path.join(ROOT, "..", "shared", "tools")]

DEFAULT_PAIRS = "nsn-ac:NSN_AC,nsn-fb:NSN_FB,nsn-nm:NSN_NM,nsn-ac-hybrid:NSN_AC"


def import_fcref():
    for d in FCREF_DIRS:
        if os.path.isfile(os.path.join(d, "fcref.py")):
            sys.path.insert(0, d)
            import fcref  # noqa: E402
            return fcref
    sys.exit("fcref.py not found (expected ../shared/tools)")


# ----------------------------------------------------------------- Siconos child
def siconos_child(path, solver, tol, max_iter, reduce_global):
    """Runs one Siconos solve and prints a JSON line (in a child process)."""
    import numpy as np
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla
    import warnings
    warnings.filterwarnings("ignore")
    import siconos.numerics as sn
    fcref = import_fcref()
    P = fcref.load(path)
    out = {}
    if P["kind"] == "local" or reduce_global:
        if P["kind"] == "local":
            W, q = P["W"].tocsc(), P["q"]
        else:
            lu = spla.splu(P["M"].tocsc())
            H = P["H"].toarray()
            MiH = lu.solve(H)
            W = sp.csc_matrix(H.T @ MiH)
            q = H.T @ lu.solve(P["f"]) + P["w"]
        nc = len(P["mu"])
        prob = sn.FrictionContactProblem(3, nc, W, q, P["mu"])
        so = sn.SolverOptions(getattr(sn, "SICONOS_FRICTION_3D_" + solver))
        so.dparam[sn.SICONOS_DPARAM_TOL] = tol
        so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = max_iter
        r, u = np.zeros(3 * nc), np.zeros(3 * nc)
        t = time.perf_counter()
        info = sn.fc3d_driver(prob, r, u, so)
        out["seconds"] = time.perf_counter() - t
        if P["kind"] == "local":
            out["error"] = float(fcref.error(P, r))
        else:
            v = lu.solve(P["H"] @ r + P["f"])
            out["error"] = float(fcref.error(P, r, v))
    else:
        nc = len(P["mu"])
        M, H = P["M"].tocsc(), P["H"].tocsc()
        prob = sn.GlobalFrictionContactProblem(3, M, H, P["f"], P["w"], P["mu"])
        so = sn.SolverOptions(getattr(sn, "SICONOS_GLOBAL_FRICTION_3D_" + solver))
        so.dparam[sn.SICONOS_DPARAM_TOL] = tol
        so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = max_iter
        r, u, v = np.zeros(3 * nc), np.zeros(3 * nc), np.zeros(M.shape[0])
        t = time.perf_counter()
        info = sn.gfc3d_driver(prob, r, u, v, so)
        out["seconds"] = time.perf_counter() - t
        out["error"] = float(fcref.error(P, r, v))
    out["info"] = int(info)
    out["iterations"] = int(so.iparam[sn.SICONOS_IPARAM_ITER_DONE])
    print("RESULT " + json.dumps(out))


def run_siconos(path, solver, tol, max_time, reduce_global=False):
    cmd = [sys.executable, os.path.abspath(__file__), "--child", path, solver, repr(tol),
           "--child-reduce" if reduce_global else "--child-native"]
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=max_time + 5)
    except subprocess.TimeoutExpired:
        return {"status": "timeout", "seconds": max_time, "error": float("inf"), "iterations": -1}
    for line in p.stdout.splitlines():
        if line.startswith("RESULT "):
            res = json.loads(line[7:])
            res["status"] = "converged" if res["error"] <= tol else "failed"
            if res["seconds"] > max_time:
                res["status"] = "timeout"
            return res
    return {"status": "crash", "seconds": float("nan"), "error": float("inf"), "iterations": -1,
            "stderr": p.stderr[-300:]}


def run_fcsolve(exe, path, solver, tol, max_time):
    cmd = [exe, "solve", path, "--solver", solver, "--tol", repr(tol), "--max-time",
           repr(max_time), "--json"]
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=max_time + 30)
    except subprocess.TimeoutExpired:
        return {"status": "timeout", "seconds": max_time, "error": float("inf"), "iterations": -1}
    try:
        res = json.loads(p.stdout)
    except json.JSONDecodeError:
        return {"status": "crash", "seconds": float("nan"), "error": float("inf"),
                "iterations": -1, "stderr": p.stderr[-300:]}
    res["status"] = "converged" if res.get("converged") and res["error"] <= tol else res["status"]
    if res["seconds"] > max_time:
        res["status"] = "timeout"
    return res


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--child":
        siconos_child(sys.argv[2], sys.argv[3], float(sys.argv[4]), 100000,
                      sys.argv[5] == "--child-reduce")
        return
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="*")
    ap.add_argument("--fcsolve", default=os.path.join(ROOT, "build", "fcsolve"))
    ap.add_argument("--data", default=DEFAULT_DATA)
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--max-time", type=float, default=20.0)
    ap.add_argument("--pairs", default=DEFAULT_PAIRS,
                    help="fcsolve-name:SICONOS_SUFFIX,... (suffix '-' = no Siconos run)")
    ap.add_argument("--no-siconos", action="store_true")
    ap.add_argument("--global-native", action="store_true",
                    help="also run Siconos gfc3d NSN_AC natively on global problems")
    ap.add_argument("--json", help="write all results here")
    ap.add_argument("--siconos-cache", help="JSON file of Siconos results, read and extended "
                    "(Siconos timings from an earlier run of the same machine)")
    ap.add_argument("--siconos-only", action="store_true", help="fill the Siconos cache only")
    args = ap.parse_args()

    have_siconos = not args.no_siconos
    if have_siconos:
        try:
            subprocess.run([sys.executable, "-c", "import siconos.numerics"], check=True,
                           capture_output=True)
        except (subprocess.CalledProcessError, FileNotFoundError):
            print("Siconos (python3-siconos) is not importable: fcsolve columns only")
            have_siconos = False
    files = args.files
    if not files:
        files = []
        for sub in ("local", "global"):
            d = os.path.join(args.data, sub)
            if os.path.isdir(d):
                files += sorted(os.path.join(d, f) for f in os.listdir(d) if f.endswith(".hdf5"))
    pairs = [p.split(":") for p in args.pairs.split(",")]
    cache = {}
    if args.siconos_cache and os.path.isfile(args.siconos_cache):
        with open(args.siconos_cache) as fh:
            cache = {tuple(k.split("|")): v for k, v in json.load(fh).items()}

    def siconos(path, solver, reduce_global):
        key = (os.path.basename(path), solver, "reduced" if reduce_global else "native")
        if key not in cache:
            cache[key] = run_siconos(path, solver, args.tol, args.max_time, reduce_global)
            if args.siconos_cache:
                with open(args.siconos_cache, "w") as fh:
                    json.dump({"|".join(k): v for k, v in cache.items()}, fh, indent=1)
        return cache[key]

    if args.siconos_only:
        for path in files:
            is_global = os.sep + "global" + os.sep in path
            for theirs in sorted({t for _, t in pairs if t != "-"}):
                s = siconos(path, theirs, is_global)
                print(f"{os.path.basename(path):50s} {theirs:8s} {s['status']:10s} "
                      f"{s['seconds']:8.3f} {s['iterations']:6d} {s['error']:9.2e}", flush=True)
            if is_global and args.global_native:
                s = siconos(path, "NSN_AC", False)
                print(f"{os.path.basename(path):50s} {'gNSN_AC':8s} {s['status']:10s} "
                      f"{s['seconds']:8.3f} {s['iterations']:6d} {s['error']:9.2e}", flush=True)
        return
    results = []
    print(f"{'problem':44s} {'fcsolve':14s} {'status':10s} {'time':>8s} {'it':>5s} {'error':>9s} | "
          f"{'siconos':12s} {'status':10s} {'time':>8s} {'it':>6s} {'error':>9s} | ratio")
    for path in files:
        name = os.path.basename(path)[:-5]
        is_global = os.sep + "global" + os.sep in path
        for ours, theirs in pairs:
            f = run_fcsolve(args.fcsolve, path, ours, args.tol, args.max_time)
            s = None
            if have_siconos and theirs != "-":
                s = siconos(path, theirs, is_global)
            ratio = ""
            if s and f["status"] == "converged" and s["status"] == "converged":
                ratio = f"{f['seconds'] / s['seconds']:.3f}"
            row = {"problem": name, "global": is_global, "fcsolve": ours, "fc": f,
                   "siconos": theirs, "sic": s}
            results.append(row)
            line = (f"{name[:44]:44s} {ours:14s} {f['status']:10s} {f['seconds']:8.3f} "
                    f"{f.get('iterations', -1):5d} {f['error']:9.2e} | ")
            if s:
                line += (f"{theirs:12s} {s['status']:10s} {s['seconds']:8.3f} "
                         f"{s['iterations']:6d} {s['error']:9.2e} | {ratio}")
            print(line, flush=True)
        if is_global and have_siconos and args.global_native:
            s = siconos(path, "NSN_AC", False)
            results.append({"problem": name, "global": True, "fcsolve": None, "fc": None,
                            "siconos": "GLOBAL_NSN_AC", "sic": s})
            print(f"{name[:44]:44s} {'':14s} {'':10s} {'':8s} {'':5s} {'':9s} | "
                  f"{'gfc3d NSN_AC':12s} {s['status']:10s} {s['seconds']:8.3f} "
                  f"{s['iterations']:6d} {s['error']:9.2e} |", flush=True)

    print("\nsummary (tol %.0e, %g s)" % (args.tol, args.max_time))
    for ours, theirs in pairs:
        rows = [r for r in results if r["fcsolve"] == ours]
        ok_f = sum(r["fc"]["status"] == "converged" for r in rows)
        line = f"  {ours:14s} solved {ok_f}/{len(rows)}"
        if have_siconos and theirs != "-":
            ok_s = sum(r["sic"]["status"] == "converged" for r in rows)
            both = [r for r in rows if r["fc"]["status"] == "converged" and r["sic"]["status"] == "converged"]
            missed = [r["problem"] for r in rows
                      if r["sic"]["status"] == "converged" and r["fc"]["status"] != "converged"]
            ratios = [r["fc"]["seconds"] / r["sic"]["seconds"] for r in both if r["sic"]["seconds"] > 0]
            med = statistics.median(ratios) if ratios else float("nan")
            line += (f" | Siconos {theirs} solved {ok_s}/{len(rows)} | both {len(both)}, "
                     f"median time ratio {med:.3f} | solved by Siconos only: {missed}")
        print(line)
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(results, fh, indent=1)


if __name__ == "__main__":
    main()
