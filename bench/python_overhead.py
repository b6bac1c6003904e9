#!/usr/bin/env python3
"""Cost of calling a solver from Python, against the same call from C++.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [--repeats N]

On 1-contact problems (where the solve itself is cheapest, so the overhead
shows most) it times, per call:
  C++      registry::solve(view, entry, request) in a C++ loop, the request
           prepared once (fcsolve._fcsolve._cpp_solve_seconds, compiled in
           the module itself, so with the same flags);
  C++ cb   the same with a no-op per-iteration callback, which the Python
           path always installs (to check for Ctrl-C): what the solver
           itself spends on a callback (time reads, calls);
  binding  the compiled entry point fcsolve._fcsolve.solve_local called
           directly (argument conversion, request, GIL release, Result);
  Python   fcsolve.solve(problem, name, tol=...) (what users call).
Each figure is the best of several rounds (rounds interleaved, to share the
machine's noise); the overhead is Python minus C++.
"""

import argparse
import timeit

import numpy as np
import scipy.sparse as sp

import fcsolve
from fcsolve import _fcsolve

PROBLEMS = {
    # W = I, mu = 0.5: sticking and sliding contacts (closed forms in python/tests)
    "sticking": ((-1.0, 0.1, 0.0), 0.5),
    "sliding": ((-1.0, 2.0, 0.0), 0.5),
}


def best_per_call(fn, repeats, rounds):
    return min(timeit.repeat(fn, number=repeats, repeat=rounds)) / repeats


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=20000)
    parser.add_argument("--rounds", type=int, default=7)
    parser.add_argument("--tol", type=float, default=1e-8)
    args = parser.parse_args()

    names = [s.name for s in fcsolve.solvers() if s.local]
    if not names:
        raise SystemExit("no solver is registered in this build of fcsolve")
    print(f"{'problem':<9} {'solver':<14} {'iters':>5} {'C++ us':>8} {'C++ cb us':>10} "
          f"{'binding us':>11} {'Python us':>10} {'overhead us':>12}")
    for label, (q, mu) in PROBLEMS.items():
        P = fcsolve.LocalProblem(sp.identity(3), np.array(q), [mu])
        for name in names:
            res = fcsolve.solve(P, name, tol=args.tol)
            tol, data, no_settings = args.tol, P._data, {}
            cpp, cpp_cb, binding, python = [], [], [], []
            for _ in range(args.rounds):
                cpp.append(_fcsolve._cpp_solve_seconds(data, name, args.repeats, tol))
                cpp_cb.append(_fcsolve._cpp_solve_seconds(data, name, args.repeats, tol, True))
                binding.append(best_per_call(
                    lambda: _fcsolve.solve_local(data, name, tol, None, None, None, None, None,
                                                 False, no_settings), args.repeats, 1))
                python.append(best_per_call(lambda: fcsolve.solve(P, name, tol=tol),
                                            args.repeats, 1))
            c, cb, b, p = (1e6 * min(x) for x in (cpp, cpp_cb, binding, python))
            print(f"{label:<9} {name:<14} {res.iterations:>5} {c:>8.2f} {cb:>10.2f} {b:>11.2f} "
                  f"{p:>10.2f} {p - c:>12.2f}")


if __name__ == "__main__":
    main()
