#!/usr/bin/env python3
"""The main job's table: every FCLIB file given solved by `auto` (the
default solver), beside the fastest single fcsolve solver on that file and,
when Siconos is importable by /usr/bin/python3, the fastest of Siconos'
solvers in SICONOS_SOLVERS (stock settings, through
python/fcsolve/campaign/siconos_runner.py, the campaign's runner).

    python3 scripts/demo_table.py [--cli build/fcsolve] [--tol 1e-8]
        [--max-time 20] [--single-max-time 5] FILE...

Each solve is one `fcsolve solve FILE --solver S --json` process; a single
solver counts when it reaches tol (fcsolve's recomputed FCLIB error).
Solvers that do not take the file's kind (global-only entries on FC/II) are
skipped. A Siconos solver counts when the FCLIB error of its solution
(recomputed by the runner with the campaign's error, the same measure)
is within tol; one that overruns its budget is stopped and does not count.
Exit status 1 if `auto` does not solve every file."""
import argparse
import json
import subprocess
from pathlib import Path

# Siconos' solvers asked on every file: its default fc3d solver (NSGS), its
# semismooth Newton, proximal point and extragradient VI on both kinds, and
# its native global Newton and interior point on FC/I.
SICONOS_SOLVERS = {"local": ["nsgs", "nsn-ac", "prox", "vi-eg"],
                   "global": ["nsgs", "nsn-ac", "prox", "vi-eg", "gnsn-ac", "ipm"]}
SICONOS_PYTHON = "/usr/bin/python3"


def siconos_available():
    p = subprocess.run([SICONOS_PYTHON, "-c", "import siconos.numerics"], capture_output=True)
    return p.returncode == 0


def siconos_best(runner, path, kind, tol, max_time):
    """The fastest Siconos solver reaching tol by the FCLIB error, or None."""
    best = None
    for s in SICONOS_SOLVERS[kind]:
        try:
            p = subprocess.run([SICONOS_PYTHON, str(runner), str(path), "--solver", s, "--tol", str(tol),
                                "--max-time", str(max_time)],
                               capture_output=True, text=True, timeout=max_time + 10)
        except subprocess.TimeoutExpired:
            continue
        if p.returncode not in (0, 1) or not p.stdout.strip():
            continue
        r = json.loads(p.stdout)
        solved = r.get("fclib_error") is not None and r["fclib_error"] <= tol
        if solved and (best is None or r["seconds"] < best["seconds"]):
            best = r
    return best


def solve(cli, path, solver, tol, max_time):
    p = subprocess.run([cli, "solve", str(path), "--solver", solver, "--tol", str(tol),
                        "--max-time", str(max_time), "--json"],
                       capture_output=True, text=True, timeout=4 * max_time + 30)
    if p.returncode not in (0, 1):
        return None  # e.g. a global-only solver given FC/II
    return json.loads(p.stdout)


def main():
    root = Path(__file__).resolve().parents[1]
    ap = argparse.ArgumentParser()
    ap.add_argument("files", nargs="+")
    ap.add_argument("--cli", default=str(root / "build" / "fcsolve"))
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--max-time", type=float, default=20, help="budget of auto")
    ap.add_argument("--single-max-time", type=float, default=5, help="budget of each single solver")
    ap.add_argument("--no-siconos", action="store_true", help="leave Siconos out")
    a = ap.parse_args()
    runner = root / "python" / "fcsolve" / "campaign" / "siconos_runner.py"
    with_siconos = not a.no_siconos and siconos_available()
    listing = json.loads(subprocess.run([a.cli, "solvers", "--json"], capture_output=True,
                                        text=True, check=True).stdout)
    singles = [e["name"] for e in listing if e["name"] != "auto"]
    print(f"{'problem':40s} {'auto':>9s} {'error':>9s} {'status':>10s} | "
          f"{'fastest single':16s} {'seconds':>9s} {'error':>9s} {'auto/best':>9s}"
          + (f" | {'siconos best':16s} {'seconds':>9s} {'auto/sic':>9s}" if with_siconos else "")
          + "  stages")
    all_solved = True
    for f in a.files:
        auto = solve(a.cli, f, "auto", a.tol, a.max_time)
        best = None
        for s in singles:
            r = solve(a.cli, f, s, a.tol, a.single_max_time)
            if r and r["converged"] and (best is None or r["seconds"] < best["seconds"]):
                best = r
        all_solved &= bool(auto and auto["converged"])
        stages = " > ".join(f"{st['solver']}({st['iterations']})" for st in auto.get("stages", []))
        b_name, b_sec, b_err, ratio = "-", float("nan"), float("nan"), float("nan")
        if best:
            b_name, b_sec, b_err = best["solver"], best["seconds"], best["error"]
            ratio = auto["seconds"] / max(b_sec, 1e-9)
        peer = ""
        if with_siconos:
            sic = siconos_best(runner, f, auto.get("kind", "local"), a.tol, a.single_max_time)
            if sic:
                peer = (f" | {sic['solver'][:16]:16s} {sic['seconds']:9.4f} "
                        f"{auto['seconds'] / max(sic['seconds'], 1e-9):9.2f}")
            else:
                peer = f" | {'none solved':16s} {float('nan'):9.4f} {float('nan'):9.2f}"
        print(f"{Path(f).stem[:40]:40s} {auto['seconds']:9.4f} {auto['error']:9.2e} "
              f"{auto['status']:>10s} | {b_name:16s} {b_sec:9.4f} {b_err:9.2e} {ratio:9.2f}{peer}  {stages}",
              flush=True)
    print("seconds: each tool's own solve time (setup and reduction included, not process start-up); "
          "problems solved in well under 1 ms are dominated by fixed costs.")
    if with_siconos:
        print(f"siconos best: the fastest of Siconos 4.4's {', '.join(SICONOS_SOLVERS['global'])} "
              f"(stock settings, {a.single_max_time:g} s each) reaching tol by the FCLIB error; "
              "auto/sic is auto's time over it.")
    else:
        print("Siconos not importable by /usr/bin/python3 (bash scripts/deps.sh --peers installs it): "
              "its column is left out.")
    return 0 if all_solved else 1


if __name__ == "__main__":
    raise SystemExit(main())
