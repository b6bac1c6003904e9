#!/usr/bin/env python3
"""Solve one FCLIB problem with several solvers and print a comparison table.

    python3 examples/python/compare_solvers.py [FILE.hdf5] [--solvers a,b,c]
                                               [--tol 1e-8] [--max-time 10]

FILE defaults to a problem bundled in examples/data; the solvers default to
three registered ones, from different families when there are several
(`python3 -c "import fcsolve; print(*fcsolve.solvers(), sep='\\n')"` lists
them). The error column is recomputed from the problem's data, independently
of what the solver reported.
"""

import argparse
from pathlib import Path

import fcsolve

DEFAULT_FILE = Path(__file__).resolve().parents[1] / "data" / "Capsules-i101-404.hdf5"


def default_solvers(count=3):
    """Up to `count` solvers, one per family first."""
    specs = fcsolve.solvers()
    chosen, families = [], set()
    for s in specs:
        if s.family not in families:
            chosen.append(s.name)
            families.add(s.family)
    chosen += [s.name for s in specs if s.name not in chosen]
    return chosen[:count]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("file", nargs="?", default=str(DEFAULT_FILE))
    parser.add_argument("--solvers", default=",".join(default_solvers()))
    parser.add_argument("--tol", type=float, default=1e-8)
    parser.add_argument("--max-time", type=float, default=10.0)
    args = parser.parse_args()

    problem = fcsolve.load(args.file)
    info = problem.info()
    print(f"{Path(args.file).name}: {info['kind']}, {info['nc']} contacts, m = {info['m']}"
          + (f", n = {info['n']}" if info["kind"] == "global" else ""))
    names = [s for s in args.solvers.split(",") if s]
    if not names:
        raise SystemExit("no solver is registered in this build of fcsolve")

    header = f"{'solver':<14} {'status':<15} {'iterations':>10} {'error':>10} {'checked':>10} {'seconds':>9}"
    print(header)
    print("-" * len(header))
    for name in names:
        res = fcsolve.solve(problem, name, tol=args.tol, max_time=args.max_time)
        if isinstance(problem, fcsolve.GlobalProblem):
            checked = problem.error(res.r, res.v)
        else:
            checked = problem.error(res.r)
        print(f"{name:<14} {res.status:<15} {res.iterations:>10} {res.error:>10.3e} "
              f"{checked:>10.3e} {res.seconds:>9.4f}")


if __name__ == "__main__":
    main()
