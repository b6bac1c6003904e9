#!/usr/bin/python3
"""Side by side: fcsolve's CLI and Siconos 4.4 on the same FCLIB files.

    /usr/bin/python3 bench/compare_siconos.py [FILES...] [--group nsgs] [--tol 1e-8]
        [--max-time 20] [--fcsolve build/fcsolve] [--json results.json]

For every file and every (fcsolve solver, Siconos solver) pair of the chosen
groups, runs `fcsolve solve FILE --solver X --tol T --max-time S --json --out
...` and the campaign's Siconos runner (python/fcsolve/campaign/
siconos_runner.py FILE --solver Y ...), each in its own process with a
wall-clock timeout, then recomputes the FCLIB error of BOTH returned
solutions with one independent implementation (the campaign's
fclib_error.py: numpy, scipy, h5py), and prints per problem the times, errors, solved flags and the
time ratio fcsolve / Siconos, then per pair the solved counts and the median
ratio over the problems both solve. "Solved" means error <= tol within the
time limit, whatever the solver says about itself.

Times are each tool's own measurement around its solve (fcsolve: the whole
registry::solve, reduction of global problems included; Siconos: the
reformulation and solver calls), not process start-up or file reading.
A pair that both sides solved in under --hot-below (10 ms) in a fresh
process is measured again on both sides in a hot loop (--hot solves in one
process, each tool's --repeat, the fastest counts), as sub-millisecond
solves must be: a fresh process' first call costs more than the solve.
Files default to ../shared/data/fclib/{local,global} beside the checkout, or
examples/data. Without siconos.numerics the Siconos column is skipped with
a message.
"""
import argparse
import glob
import json
import os
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
CAMPAIGN = os.path.join(ROOT, "python", "fcsolve", "campaign")
sys.path.insert(0, CAMPAIGN)  # the runner and the error measure, as plain modules
import fclib_error  # noqa: E402
from siconos_runner import SOLVERS as SICONOS_SOLVERS  # noqa: E402  (imports no siconos)

# Groups of (fcsolve solver + extra CLI args, Siconos runner solver) pairs.
# Each solver family adds its group (e.g. "newton": nsn-ac <-> NSN-AC, ...).
PAIRS = {
    # Siconos NSGS with its stock settings (light error each sweep, the full one
    # at the end), as its users run it; and the tuned set-up that computes the
    # full error every sweep, shown beside it, never instead of it.
    "nsgs": [("nsgs", [], "nsgs"), ("nsgs", [], "nsgs-full-error")],
    "nsgs-variants": [
        ("psor", [], "nsgs"),
        ("nsgs-ac", [], "nsgs"),
        ("nsgs-hybrid", [], "nsgs"),
        ("nsgs-fb", [], "nsgs"),
        ("nsgs-proj", [], "nsgs"),
        ("nsgs", ["--ordering", "reshuffle"], "nsgs-shuffle"),
    ],
    "newton": [("nsn-ac", [], "nsn-ac"), ("nsn-fb", [], "nsn-fb"), ("nsn-nm", [], "nsn-nm"),
               ("nsn-jm", [], "nsn-jm"), ("nsn-ac-hybrid", [], "nsn-ac")],
    # FC/I natively (global files only): fcsolve in (v, r) vs Siconos gfc3d NSN-AC
    "newton-global": [("nsn-ac-global", [], "gnsn-ac"), ("nsn-fb-global", [], "gnsn-ac")],
    # interior-point family on global problems (gfc3d_driver for Siconos)
    # proximal point: inner Newton (as Siconos' PROX) or inner NSGS, both against PROX
    "ppa": [("ppa", [], "prox"), ("ppa-nsgs", [], "prox")],
    # fixed points: De Saxce's (fixed rho as DSFP, and the self-adaptive
    # step), Tresca's, Panagiotopoulos'
    "fixed-point": [("fp-ds", [], "dsfp"), ("fp-ds", ["--step", "self-adaptive"], "dsfp"),
                    ("tresca", [], "tresca"), ("pana", [], "pfp")],
    # VI projection family: fixed point and extragradient, self-adaptive step;
    # vi-eg's default second step is VI_EG's (from the trial point), the
    # textbook one (Korpelevich's, from r) is shown too
    "vi": [("vi-fp", [], "vi-fp"), ("vi-eg", [], "vi-eg"),
           ("vi-eg", ["--second-step", "korpelevich"], "vi-eg")],
    # ADMM with De Saxce's shift against Siconos' ADMM
    "admm": [("admm", [], "admm")],
    # ADMM on FC/I in (v, r) (global files only) against Siconos' gfc3d ADMM
    "admm-global": [("admm-global", [], "gadmm")],
    "ipm": [("nipm", [], "ipm"), ("aclm-newton", [], "ipm"), ("nipm", [], "gnsgs-wr"),
            ("nipm", [], "gnsn-ac")],
}


def default_files():
    shared = os.path.join(ROOT, "..", "shared", "data", "fclib")
    if os.path.isdir(os.path.join(shared, "local")):
        return sorted(glob.glob(os.path.join(shared, "local", "*.hdf5"))) + \
            sorted(glob.glob(os.path.join(shared, "global", "*.hdf5")))
    return sorted(glob.glob(os.path.join(ROOT, "examples", "data", "*.hdf5")))


def siconos_available():
    try:
        subprocess.run([sys.executable, "-c", "import siconos.numerics"], check=True,
                       capture_output=True, timeout=60)
        return True
    except (subprocess.SubprocessError, OSError):
        return False


def run_json(cmd, timeout):
    """Runs cmd, returns (last JSON line as dict or None, note)."""
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, "killed after %.0f s" % timeout
    for line in reversed(proc.stdout.strip().splitlines()):
        try:
            return json.loads(line), ""
        except ValueError:
            continue
    return None, (proc.stderr.strip().splitlines() or ["no output"])[-1]


def run_timed(cmd, timeout, repeat):
    """Runs cmd; short runs are repeated up to
    `repeat` times and the smallest reported time kept (the machine is shared
    and noisy; the solvers are deterministic)."""
    reported, note = run_json(cmd, timeout)
    best = reported
    for _ in range(repeat - 1):
        if best is None or float(best.get("seconds", 1e9)) > 1.0:
            break
        again, _ = run_json(cmd, timeout)
        if again is not None and _seconds(again) < _seconds(best):
            best = again
    return best, note


def _seconds(reported):
    # fcsolve: setup + solve (compute() and solve(), the reduction of a global
    # problem included); the registry's validation and error check are left
    # out, as the runner leaves out its own error check
    if "solve_seconds" in reported:
        return float(reported["setup_seconds"]) + float(reported["solve_seconds"])
    return float(reported.get("seconds", float("nan")))


def measure(problem, path, reported, note, max_time, tol):
    """dict(seconds, error, solved, note) judged by the independent error."""
    out = dict(seconds=float("nan"), error=float("inf"), solved=False, note=note)
    if reported is None or not os.path.exists(path):
        return out
    out["seconds"] = _seconds(reported)
    try:
        r, v, lam = fclib_error.read_solution(path)
        out["error"] = fclib_error.error(problem, r, v, lam)
    except (OSError, KeyError, ValueError) as e:
        out["note"] = "unreadable solution: %s" % e
        return out
    out["solved"] = bool(out["error"] <= tol and out["seconds"] <= max_time)
    if not out["note"]:
        out["note"] = reported.get("status", "")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="*")
    ap.add_argument("--group", action="append", choices=sorted(PAIRS),
                    help="pair groups to run (default: nsgs)")
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--max-time", type=float, default=20.0)
    ap.add_argument("--repeat", type=int, default=3,
                    help="runs of each solve under 1 s; the fastest counts")
    ap.add_argument("--hot", type=int, default=200,
                    help="pairs both sides solved in under --hot-below seconds (first call of a "
                         "fresh process) are measured again on both sides in a hot loop: this "
                         "many solves in one process (each tool's --repeat), the fastest counts; "
                         "0: never")
    ap.add_argument("--hot-below", type=float, default=0.01)
    ap.add_argument("--margin", type=float, default=30.0, help="extra seconds before a process is killed")
    ap.add_argument("--fcsolve", default=os.path.join(ROOT, "build", "fcsolve"))
    ap.add_argument("--json", help="write every measurement to this file")
    args = ap.parse_args()
    files = args.files or default_files()
    pairs = [p for g in (args.group or ["nsgs"]) for p in PAIRS[g]]
    if not os.path.exists(args.fcsolve):
        sys.exit("fcsolve CLI not found at %s (build it: cmake --build build --target fcsolve_cli)"
                 % args.fcsolve)
    with_siconos = siconos_available()
    if not with_siconos:
        print("note: `import siconos.numerics` fails for %s: Siconos columns skipped "
              "(Debian: apt-get install python3-siconos)" % sys.executable)
    runner = os.path.join(CAMPAIGN, "siconos_runner.py")
    timeout = args.max_time + args.margin
    rows = []
    siconos_done = {}
    print("%-36s %-22s %-13s %10s %9s %3s | %10s %9s %3s | %7s" % (
        "problem", "fcsolve", "siconos", "fc s", "fc err", "ok", "sic s", "sic err", "ok", "ratio"))
    with tempfile.TemporaryDirectory() as tmp:
        for path in files:
            name = os.path.splitext(os.path.basename(path))[0]
            try:
                problem = fclib_error.load_problem(path)
                problem.free_velocity_norm()  # factorises M once, here
            except (ValueError, KeyError, OSError) as e:
                print("%-36s skipped: %s" % (name, e))
                continue
            kind = problem.kind
            for fc_name, fc_args, sic_name in pairs:
                label = " ".join([fc_name] + fc_args)
                if (SICONOS_SOLVERS[sic_name]["local"] if kind == "local"
                        else SICONOS_SOLVERS[sic_name]["global_"]) is None:
                    continue  # no Siconos solver of that name for this kind (ipm: global only)
                fc_out = os.path.join(tmp, "fc.hdf5")
                sic_out = os.path.join(tmp, "sic.hdf5")
                for f in (fc_out, sic_out):
                    if os.path.exists(f):
                        os.remove(f)
                rep, note = run_timed([args.fcsolve, "solve", path, "--solver", fc_name, "--tol",
                                       repr(args.tol), "--max-time", repr(args.max_time),
                                       "--max-iter", "1000000000", "--json", "--out", fc_out]
                                      + fc_args, timeout, args.repeat)
                fc = measure(problem, fc_out, rep, note, args.max_time, args.tol)
                sic = dict(seconds=float("nan"), error=float("nan"), solved=False, note="skipped")
                if (path, sic_name) in siconos_done:  # pairs sharing a Siconos solver
                    sic = siconos_done[(path, sic_name)]
                elif with_siconos:
                    rep, note = run_timed([sys.executable, runner, path, "--solver", sic_name,
                                           "--tol", repr(args.tol), "--max-time", repr(args.max_time),
                                           "--out", sic_out], timeout, args.repeat)
                    sic = measure(problem, sic_out, rep, note, args.max_time, args.tol)
                    siconos_done[(path, sic_name)] = sic
                # both solved, both fast: a slow side repeated would only
                # add its own seconds N times over
                hot = args.hot > 1 and with_siconos and fc["solved"] and sic["solved"] and \
                    max(fc["seconds"], sic["seconds"]) < args.hot_below
                if hot:
                    # a fresh process' first call (page faults, caches, lazy
                    # set-up) costs more than a sub-millisecond solve on both
                    # sides: measure both in a hot loop instead
                    rep, note = run_json([args.fcsolve, "solve", path, "--solver", fc_name, "--tol",
                                          repr(args.tol), "--max-time", repr(args.max_time),
                                          "--max-iter", "1000000000", "--json", "--out", fc_out,
                                          "--repeat", str(args.hot)] + fc_args, timeout)
                    fc = measure(problem, fc_out, rep, note, args.max_time, args.tol)
                    key = (path, sic_name, "hot")
                    if key not in siconos_done:
                        rep, note = run_json([sys.executable, runner, path, "--solver", sic_name,
                                              "--tol", repr(args.tol), "--max-time", repr(args.max_time),
                                              "--out", sic_out, "--repeat", str(args.hot)], timeout)
                        siconos_done[key] = measure(problem, sic_out, rep, note, args.max_time, args.tol)
                    sic = siconos_done[key]
                fc["hot"] = sic["hot"] = hot
                ratio = fc["seconds"] / sic["seconds"] if fc["solved"] and sic["solved"] \
                    and sic["seconds"] > 0 else float("nan")
                rows.append(dict(problem=name, fcsolve=label, siconos=sic_name, fc=fc, sic=sic,
                                 ratio=ratio))
                print("%-36s %-22s %-13s %10.6f %9.2e %3s | %10.6f %9.2e %3s | %7.3f %s%s" % (
                    name[:36], label[:22], sic_name, fc["seconds"], fc["error"],
                    "yes" if fc["solved"] else "no", sic["seconds"], sic["error"],
                    "yes" if sic["solved"] else "no", ratio, "hot " if hot else "",
                    "; ".join(x for x in ("fc: " + fc["note"] if not fc["solved"] else "",
                                          "sic: " + sic["note"] if with_siconos and not sic["solved"]
                                          else "") if x)), flush=True)
    print()
    print("tol %.1e, time limit %.0f s; ratio = fcsolve seconds / Siconos seconds" % (args.tol, args.max_time))
    for fc_name, fc_args, sic_name in pairs:
        label = " ".join([fc_name] + fc_args)
        sel = [r for r in rows if r["fcsolve"] == label and r["siconos"] == sic_name]
        ratios = [r["ratio"] for r in sel if r["ratio"] == r["ratio"]]
        fc_only = [r["problem"] for r in sel if r["fc"]["solved"] and not r["sic"]["solved"]]
        sic_only = [r["problem"] for r in sel if r["sic"]["solved"] and not r["fc"]["solved"]]
        if not with_siconos:
            print("%-22s: fcsolve solved %d/%d (Siconos not run)"
                  % (label, sum(r["fc"]["solved"] for r in sel), len(sel)))
            continue
        # Sub-millisecond solves: with --hot, timed in a hot loop on both
        # sides (rows marked "hot"); the ratio over the problems both take
        # >= 1 ms for is reported apart as well.
        slow = [r["ratio"] for r in sel if r["ratio"] == r["ratio"]
                and min(r["fc"]["seconds"], r["sic"]["seconds"]) >= 1e-3]
        n_hot = sum(1 for r in sel if r["ratio"] == r["ratio"] and r["fc"].get("hot"))
        print("%-22s vs %-13s: fcsolve solved %d/%d, Siconos %d/%d, both %d, median ratio %s"
              " (%d of them timed in a hot loop; %s over the %d both take >= 1 ms for)"
              % (label, sic_name, sum(r["fc"]["solved"] for r in sel), len(sel),
                 sum(r["sic"]["solved"] for r in sel), len(sel), len(ratios),
                 "%.3f" % statistics.median(ratios) if ratios else "n/a", n_hot,
                 "%.3f" % statistics.median(slow) if slow else "n/a", len(slow)))
        if sic_only:
            print("    solved by Siconos only: " + ", ".join(sic_only))
        if fc_only:
            print("    solved by fcsolve only: " + ", ".join(fc_only))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(dict(tol=args.tol, max_time=args.max_time, rows=rows), f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
