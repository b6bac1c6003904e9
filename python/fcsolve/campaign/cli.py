"""Command line of the campaign: `fcsolve bench ...` and `fcsolve report DIR`
(the fcsolve binary forwards both here), or `python3 -m fcsolve.campaign`."""
import argparse
import os
import sys

from .results import FAILURE_CLASSES
from .solvers import DEFAULT_PEER_PYTHON

BENCH_EXAMPLES = """examples:
  fcsolve bench examples/data/*.hdf5 --out campaign --report
  fcsolve bench ../shared/data/fclib --solvers all,siconos:nsgs,siconos:nsn-ac \\
                --tol 1e-4,1e-8 --timeout 20 --jobs 2 --out campaign
  fcsolve bench PROBLEMS --dask tcp://scheduler:8786 --out /shared/campaign
"""


def _tolerances(text):
    try:
        tols = [float(t) for t in text.split(",") if t.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a list of numbers")
    if not tols or any(not t > 0 for t in tols):
        raise argparse.ArgumentTypeError("tolerances must be positive")
    return sorted(set(tols), reverse=True)


def _classes(text):
    classes = [c.strip() for c in text.split(",") if c.strip()]
    unknown = [c for c in classes if c not in FAILURE_CLASSES]
    if unknown:
        raise argparse.ArgumentTypeError(f"unknown failure class {unknown} (known: {FAILURE_CLASSES})")
    return classes


def parser():
    ap = argparse.ArgumentParser(prog="fcsolve", description="benchmark campaigns of fcsolve")
    sub = ap.add_subparsers(dest="command", required=True)
    b = sub.add_parser("bench", help="run every problem x solver x tolerance into DIR/results.csv",
                       epilog=BENCH_EXAMPLES, formatter_class=argparse.RawDescriptionHelpFormatter)
    b.add_argument("problems", nargs="+", help="FCLIB files, folders (searched recursively) or globs")
    b.add_argument("--solvers", default="all",
                   help="comma list: fcsolve solver names, 'all' (every registered solver, the "
                        "default), peers as PEER:NAME or PEER:all (siconos:nsgs, siconos:all)")
    b.add_argument("--tol", type=_tolerances, default=[1e-8],
                   help="tolerance or comma list for a sweep (1e-2,1e-4,1e-6,1e-8); default 1e-8")
    b.add_argument("--timeout", type=float, default=20.0,
                   help="seconds per run (the solver's --max-time; the process is killed "
                        "--grace seconds later); default 20")
    b.add_argument("--grace", type=float, default=2.0, help="see --timeout; default 2")
    b.add_argument("--max-iter", type=int, help="iteration budget for every solver "
                                                "(default: each solver's own)")
    b.add_argument("--out", default="campaign", help="results folder; default ./campaign")
    b.add_argument("--jobs", type=int, default=None, help="parallel runs; default: the CPU count")
    b.add_argument("--dask", metavar="ADDRESS", help="run on a Dask distributed scheduler")
    b.add_argument("--fcsolve", help="the fcsolve binary (default: the one that called, "
                                     "$FCSOLVE_CLI, PATH, ./build/fcsolve)")
    b.add_argument("--peer-python", default=DEFAULT_PEER_PYTHON,
                   help=f"Python for the peer runners; default {DEFAULT_PEER_PYTHON}")
    b.add_argument("--redo", type=_classes, default=[],
                   help="run again the runs of these failure classes (e.g. crash,timeout)")
    b.add_argument("--repeat", type=int, default=1,
                   help="run each solve N times and keep the fastest time (short runs are noisy); "
                        "default 1")
    b.add_argument("--hot-below", type=float, default=None, metavar="SECONDS",
                   help="time solved runs faster than this again as the fastest of many solves "
                        "in one process (the command's --repeat); 0: fresh processes only; "
                        "default 0.1")
    b.add_argument("--keep-solutions", action="store_true", help="keep DIR/solutions/*.hdf5")
    b.add_argument("--report", action="store_true", help="then write the report (fcsolve report)")
    r = sub.add_parser("report", help="charts and an HTML page from DIR/results.csv")
    r.add_argument("dir", help="the campaign folder (bench --out)")
    r.add_argument("--out", help="where to write the report; default DIR/report")
    return ap


def main(argv=None):
    a = parser().parse_args(argv)
    try:
        if a.command == "bench":
            from .runner import run_campaign

            if a.jobs is not None and a.jobs < 1:
                raise RuntimeError("--jobs must be at least 1")
            run_campaign(a.problems, solvers=a.solvers, tols=a.tol, timeout=a.timeout,
                         out_dir=a.out, jobs=a.jobs, dask=a.dask, fcsolve=a.fcsolve,
                         peer_python=a.peer_python, max_iter=a.max_iter, grace=a.grace,
                         redo=a.redo, keep_solutions=a.keep_solutions, repeat=a.repeat,
                         **({} if a.hot_below is None else dict(hot_below=a.hot_below)))
            if not a.report:
                return 0
            report_dir = a.out
        else:
            report_dir = a.dir
            if not os.path.isdir(report_dir):
                raise RuntimeError(f"{report_dir} is not a campaign folder")
        from .report import build_report

        page = build_report(report_dir, getattr(a, "out", None) if a.command == "report" else None)
        print(f"fcsolve report: {page}")
        return 0
    except KeyboardInterrupt:
        print("\nfcsolve: interrupted; finished runs are in the CSV (rerun to resume)",
              file=sys.stderr)
        return 130
    except (RuntimeError, ValueError, OSError) as e:
        print(f"fcsolve: {e}", file=sys.stderr)
        return 2
