"""fcsolve: solvers for discrete frictional contact problems with Coulomb
friction, the reduced problem FC/II (W, q, mu) and the global problem FC/I
(M, H, f, w, mu), as stored in the FCLIB HDF5 format.

    import fcsolve
    P = fcsolve.load("examples/data/Capsules-i101-404.hdf5")   # LocalProblem
    res = fcsolve.solve(P, "nsgs", tol=1e-8)
    print(res.status, res.iterations, res.error, P.error(res.r))
    for s in fcsolve.solvers():
        print(s)

Problems: LocalProblem(W, q, mu, d=3), GlobalProblem(M, H, f, w, mu, G, b, d=3),
load(path), save(path, problem, solution, guesses), load_solution, load_guesses;
problem.error(r), problem.info(), problem.diagnostics(), check_existence(problem),
GlobalProblem.reduce().
Solving: solve(problem, solver, tol, ...) -> Result; solvers(); solver(name);
Settings(name, **values) for typed, reusable solver settings.
Errors: InvalidProblemError and UsageError (ValueError), FclibError (OSError).
"""

import numpy as _numpy

from . import _fcsolve

if _fcsolve._pybind11_version < (2, 12) and int(_numpy.__version__.split(".")[0]) >= 2:
    raise ImportError(
        f"this fcsolve module was built with pybind11 {_fcsolve._pybind11_version}, which does "
        f"not support numpy {_numpy.__version__}: install it with `pip install .` (pybind11 "
        "from PyPI) or run it with the system's numpy 1.x (/usr/bin/python3)")

from ._fcsolve import (
    FclibError,
    InvalidProblemError,
    Result,
    Settings,
    UsageError,
    __version__,
)
from ._problems import (
    GlobalProblem,
    LocalProblem,
    check_existence,
    load,
    load_guesses,
    load_solution,
    save,
)
from ._solve import SettingSpec, SolverSpec, solve, solver, solvers

for _cls in (Result, Settings):
    _cls.__module__ = __name__
del _cls

__all__ = [
    "FclibError",
    "GlobalProblem",
    "InvalidProblemError",
    "LocalProblem",
    "Result",
    "SettingSpec",
    "Settings",
    "SolverSpec",
    "UsageError",
    "__version__",
    "check_existence",
    "load",
    "load_guesses",
    "load_solution",
    "save",
    "solve",
    "solver",
    "solvers",
]
