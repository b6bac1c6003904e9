"""Solving: fcsolve.solve and the solver catalogue (fcsolve.solvers)."""

import numbers
from dataclasses import dataclass
from functools import lru_cache

from . import _fcsolve
from ._fcsolve import Result, UsageError


@dataclass(frozen=True)
class SettingSpec:
    """One setting of a solver: name, type ('real', 'integer', 'boolean',
    'choice'), default, doc, choices (for 'choice'), allowed range [min, max]."""

    name: str
    type: str
    default: object
    doc: str
    choices: tuple
    min: float
    max: float

    def __str__(self):
        allowed = f" {{{', '.join(self.choices)}}}" if self.choices else ""
        if self.type in ("real", "integer") and (self.min > float("-inf") or self.max < float("inf")):
            allowed = f" in [{self.min:g}, {self.max:g}]"
        return f"{self.name}: {self.type} = {self.default!r}{allowed}  {self.doc}"


@dataclass(frozen=True)
class SolverSpec:
    """A registered solver: name (what fcsolve.solve takes), family,
    summary, settings (SettingSpec tuple), needs_symmetric (run on (W + W^T)/2
    when W is not symmetric), default_max_iter, local (solves FC/II),
    global_native (solves FC/I without reduction; others reduce)."""

    name: str
    family: str
    summary: str
    settings: tuple
    needs_symmetric: bool
    default_max_iter: int
    local: bool
    global_native: bool

    def __str__(self):
        lines = [f"{self.name} [{self.family}]: {self.summary}"
                 + ("  (symmetric W)" if self.needs_symmetric else "")]
        lines += [f"    {s}" for s in self.settings]
        return "\n".join(lines)


@lru_cache(maxsize=None)
def _catalogue():
    out = []
    for e in _fcsolve.solvers():
        settings = tuple(SettingSpec(s["name"], s["type"], s["default"], s["doc"],
                                     tuple(s["choices"]), s["min"], s["max"])
                         for s in e["settings"])
        out.append(SolverSpec(e["name"], e["family"], e["summary"], settings,
                              e["needs_symmetric"], e["default_max_iter"], e["local"],
                              e["global_native"]))
    return tuple(out)


def solvers():
    """Every solver this build of fcsolve registers, as a list of SolverSpec
    (name, family, summary, settings with types, defaults and docs). print()
    one for a readable description."""
    return list(_catalogue())


def solver(name):
    """The SolverSpec of one solver; fcsolve.UsageError if it is unknown."""
    for s in _catalogue():
        if s.name == name:
            return s
    names = ", ".join(s.name for s in _catalogue()) or "none is registered"
    raise UsageError(f"unknown solver '{name}' (available: {names})")


def solve(problem, solver="auto", tol=1e-8, max_iter=None, max_time=None, r0=None, v0=None,
          callback=None, history=False, **solver_settings):
    """Solves a LocalProblem or GlobalProblem with a solver of the catalogue.

    problem: fcsolve.LocalProblem or fcsolve.GlobalProblem.
    solver: a solver name (see fcsolve.solvers() and the list below) or an
        fcsolve.Settings object (a solver name with checked settings). The
        default, 'auto', runs a staged plan over the other solvers (NSGS
        sweeps, semismooth Newton, fallbacks), each stage from the best
        iterate so far; Result.stages says what it ran and why.
    tol: target FCLIB relative error (the error of LocalProblem.error).
    max_iter: iteration budget (None: the solver's default_max_iter; for
        'auto', the iterations of all its stages together).
    max_time: wall-clock budget in seconds (None: unlimited).
    r0, v0: warm start for r (and v for global problems); a previous Result
        may be passed as r0 (its r and v are used).
    callback: callable(iteration, error, seconds), called after each
        iteration. SciPy's convention (scipy.optimize.minimize): returning
        True or raising StopIteration stops the solve (status 'stopped');
        None or False goes on. Any other exception it raises stops the solve
        and is raised again.
    history: keep the error of every iteration in Result.history.
    **solver_settings: the solver's own settings (e.g. omega=1.2), checked:
        an unknown name or an out-of-range value raises fcsolve.UsageError (a
        ValueError), a value of the wrong type raises TypeError.

    Returns an fcsolve.Result (r, u, v, status, converged, iterations, error,
    seconds, history, message...). `converged` is True only when the FCLIB
    error of the returned solution, recomputed from the problem's data, is
    <= tol. Numerical failure is a status, never an exception; invalid input
    raises fcsolve.InvalidProblemError / UsageError (ValueError) or TypeError.

    Global problems are solved natively by solvers that can, otherwise
    reduced to W = H^T M^-1 H and v recovered. The GIL is released while the
    solver runs (other Python threads go on); Ctrl-C stops a long solve
    within ~50 ms of the next iteration and raises KeyboardInterrupt.
    """
    try:
        impl, data = problem._solve_impl, problem._data
    except AttributeError:
        raise TypeError("problem must be an fcsolve.LocalProblem or fcsolve.GlobalProblem, "
                        f"got {type(problem).__name__}") from None
    if isinstance(r0, Result):
        r0, v0 = r0.r, (r0.v if v0 is None else v0)
    _check_number("tol", tol)
    if max_time is not None:
        _check_number("max_time", max_time)
    if max_iter is not None and (isinstance(max_iter, bool) or not isinstance(max_iter, numbers.Integral)):
        raise TypeError(f"max_iter must be an integer or None, got {max_iter!r}")
    return impl(data, solver, tol, max_iter, max_time, r0, v0, callback, history,
                solver_settings)


def _catalogue_doc():
    specs = _catalogue()
    if not specs:
        return "\n\nSolvers in this build: none is registered."
    return "\n\nSolvers in this build (settings: type = default):\n\n" + "\n".join(
        str(s) for s in specs)


solve.__doc__ += _catalogue_doc()


def _check_number(name, value):
    """A real number (not a string, not a bool): pybind11's own message for
    tol='1e-8' ("incompatible function arguments") names nothing."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a real number, got {value!r} ({type(value).__name__})")
