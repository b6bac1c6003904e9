"""Solving from Python: every registered solver on closed-form cases and real
FCLIB problems (checked by fcref's error), warm starts, callbacks, typed
settings, the GIL and Ctrl-C."""

import math
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp

import fcsolve
from conftest import SOLVER_NAMES, data_file, reference_error, solver_params

# Small problems every solver must solve (tol 1e-8).
EASY = ["FC3D_Example1.hdf5", "Rover1039.hdf5", "GFC3D_Example1.hdf5"]
# Larger ones: a solver may fail within the budget, but never claim a false
# convergence, and its reported error must be fcref's.
HARDER = ["Confeti-ex03-Fc3D-SBM.hdf5", "OneObject-i1028-138.hdf5", "Box_Stacks-i0035-31-0.hdf5"]


# ipm-socqp solves the convex SOCQP with the friction term frozen at s = 0
# (the associated friction law), not the Coulomb problem: it must report its
# Coulomb error honestly, but is not expected to converge where sliding occurs.
ASSOCIATED_LAW = {"ipm-socqp"}
# Interior-point methods (family "ipm") restart from an interior point: r0
# is accepted (ACLM takes its slip speeds from it) but does not shorten the solve.
NO_WARM_START_FAMILIES = {"ipm"}


def local_solvers():
    return [s.name for s in fcsolve.solvers() if s.local]


def global_only(solver):
    """A solver of FC/I only (e.g. nsn-ac-global): it gets global problems."""
    return solver is not None and solver not in local_solvers()


def one_contact(q, mu=0.5, solver=None):
    """u = r + q with W = I; for a global-only solver the same contact as
    FC/I with M = I, H = I, f = q, w = 0 (v = r + q, u = v)."""
    q = np.array(q, dtype=float)
    if global_only(solver):
        return fcsolve.GlobalProblem(sp.identity(3), sp.identity(3), q, np.zeros(3), [mu])
    return fcsolve.LocalProblem(sp.identity(3), q, [mu])


def real_problem(solver, local_name, global_name="Box_Stacks-i0035-31-0.hdf5"):
    """A local FCLIB problem, or a global one of a similar size for a
    global-only solver."""
    return fcsolve.load(data_file(global_name if global_only(solver) else local_name))


def error_of(P, res):
    return P.error(res.r, res.v) if isinstance(P, fcsolve.GlobalProblem) else P.error(res.r)


# Closed forms with W = I (u = r + q), mu = 0.5:
#   take-off  q = ( 1, 0.3, 0): r = 0, u = q
#   sticking  q = (-1, 0.1, 0): r = (1, -0.1, 0), u = 0 (0.1 <= 0.5 * 1)
#   sliding   q = (-1, 2, 0):   r = (1, -0.5, 0), u = (0, 1.5, 0): r on the cone
#             boundary, opposite to the slip, u_N = 0
CLOSED_FORMS = {
    "take-off": ((1.0, 0.3, 0.0), (0.0, 0.0, 0.0)),
    "sticking": ((-1.0, 0.1, 0.0), (1.0, -0.1, 0.0)),
    "sliding": ((-1.0, 2.0, 0.0), (1.0, -0.5, 0.0)),
}


@pytest.mark.parametrize("solver", solver_params())
@pytest.mark.parametrize("case", sorted(CLOSED_FORMS))
def test_closed_forms(solver, case):
    q, expected = CLOSED_FORMS[case]
    P = one_contact(q, solver=solver)
    res = fcsolve.solve(P, solver, tol=1e-10)
    assert res.error == pytest.approx(error_of(P, res), rel=1e-12, abs=1e-300)
    if case == "sliding" and solver in ASSOCIATED_LAW:
        assert not res.converged and res.error > 1e-3  # s = 0 cannot slide
        return
    assert res.converged, res
    np.testing.assert_allclose(res.r, expected, atol=1e-8)
    np.testing.assert_allclose(res.u, np.array(expected) + q, atol=1e-8)
    assert error_of(P, res) <= 1e-10


def check_result(path, P, res, tol):
    """The result is honest: its error is the independent one, no NaN, and
    'converged' holds exactly when that error is within tol."""
    assert res.r.shape == (P.size,) and np.isfinite(res.r).all()
    v = res.v if isinstance(P, fcsolve.GlobalProblem) else None
    if v is not None:
        assert v.shape == (P.num_dofs,) and np.isfinite(v).all()
    ref = reference_error(path, P, np.asarray(res.r), None if v is None else np.asarray(v))
    assert res.error == pytest.approx(ref, rel=1e-6, abs=1e-14), (res, ref)
    assert res.converged == (ref <= tol * (1 + 1e-9)), (res, ref)
    return ref


def solve_and_check(solver, name, tol, max_time):
    """Solves a file's problem (skipping a local one for a global-only
    solver) and checks the result with check_result."""
    path = data_file(name)
    P = fcsolve.load(path)
    if isinstance(P, fcsolve.LocalProblem) and solver not in local_solvers():
        pytest.skip(f"{solver} does not solve local problems")
    res = fcsolve.solve(P, solver, tol=tol, max_time=max_time)
    check_result(path, P, res, tol)
    return res


@pytest.mark.parametrize("solver", solver_params())
@pytest.mark.parametrize("name", EASY)
def test_every_solver_solves_small_real_problems(solver, name):
    res = solve_and_check(solver, name, tol=1e-8, max_time=20)
    if solver not in ASSOCIATED_LAW:
        assert res.converged, f"{solver} on {name}: {res} {res.message}"


@pytest.mark.parametrize("solver", solver_params())
@pytest.mark.parametrize("name", HARDER)
def test_every_solver_is_honest_on_larger_problems(solver, name):
    res = solve_and_check(solver, name, tol=1e-6, max_time=5)
    assert res.status in {"converged", "max-iterations", "timeout", "stalled", "diverged", "nan"}


@pytest.mark.parametrize("solver", solver_params())
def test_warm_start_reduces_iterations(solver):
    P = real_problem(solver, "Confeti-ex03-Fc3D-SBM.hdf5")
    cold = fcsolve.solve(P, solver, tol=1e-6, max_time=20)
    if not cold.converged:
        pytest.skip(f"{solver} does not converge from scratch here: {cold}")
    assert cold.iterations > 1
    warm = fcsolve.solve(P, solver, tol=1e-6, r0=cold.r)
    assert warm.converged, (cold, warm)
    if fcsolve.solver(solver).family in NO_WARM_START_FAMILIES:
        pytest.skip(f"{solver} restarts from an interior point: r0 does not shorten the solve")
    assert warm.iterations < cold.iterations, (cold, warm)
    again = fcsolve.solve(P, solver, tol=1e-6, r0=cold)  # a Result works as r0
    assert again.iterations == warm.iterations


@pytest.mark.parametrize("solver", solver_params())
def test_callback_sees_each_iteration_and_can_stop(solver):
    P = real_problem(solver, "Confeti-ex03-Fc3D-SBM.hdf5")
    calls = []

    def callback(iteration, error, seconds):
        calls.append((iteration, error, seconds))
        return iteration >= 3  # SciPy's convention: True stops

    res = fcsolve.solve(P, solver, tol=1e-14, max_iter=10000, callback=callback)
    if len(calls) == 0:
        pytest.fail(f"{solver} never called the callback")
    assert res.status == "stopped" and not res.converged, res
    assert [c[0] for c in calls] == [1, 2, 3]
    assert res.iterations == 3
    assert all(isinstance(e, float) and isinstance(s, float) for _, e, s in calls)
    assert [c[2] for c in calls] == sorted(c[2] for c in calls)
    # the result is still an honest one (its error is that of its r)
    assert res.error == pytest.approx(error_of(P, res), rel=1e-10)


@pytest.mark.parametrize("solver", solver_params())
def test_callback_returning_none_goes_on_and_exceptions_propagate(solver):
    P = one_contact((-1.0, 2.0, 0.0), solver=solver)
    seen = []
    res = fcsolve.solve(P, solver, tol=1e-10, callback=lambda i, e, s: seen.append(i))
    assert res.converged or solver in ASSOCIATED_LAW, res
    assert seen == list(range(1, len(seen) + 1))

    def failing(iteration, error, seconds):
        raise ZeroDivisionError("from the callback")

    Q = real_problem(solver, "Confeti-ex03-Fc3D-SBM.hdf5")
    with pytest.raises(ZeroDivisionError, match="from the callback"):
        fcsolve.solve(Q, solver, tol=1e-14, callback=failing)


@pytest.mark.parametrize("solver", solver_params())
def test_callback_raising_stop_iteration_stops(solver):
    P = real_problem(solver, "Confeti-ex03-Fc3D-SBM.hdf5")
    seen = []

    def stop_at_two(iteration, error, seconds):
        seen.append(iteration)
        if iteration >= 2:
            raise StopIteration

    res = fcsolve.solve(P, solver, tol=1e-14, max_iter=10000, callback=stop_at_two)
    assert res.status == "stopped" and not res.converged, res
    assert seen == [1, 2]
    assert res.error == pytest.approx(error_of(P, res), rel=1e-10)
    # False goes on, like None
    res = fcsolve.solve(P, solver, tol=1e-14, max_iter=4, callback=lambda i, e, s: False)
    assert res.status != "stopped", res


@pytest.mark.parametrize("solver", solver_params())
def test_history(solver):
    P = real_problem(solver, "FC3D_Example1.hdf5", "GFC3D_Example1.hdf5")
    res = fcsolve.solve(P, solver, tol=1e-8, history=True)
    # one entry per iteration at most, plus the starting point (a solver may
    # record an estimate, or skip the sweep in which it checks the full error)
    assert 0 < len(res.history) <= res.iterations + 1
    assert np.isfinite(res.history).all() and (res.history >= 0).all()
    assert len(fcsolve.solve(P, solver, tol=1e-8).history) == 0


# ---------------------------------------------------------------- catalogue, settings

def test_catalogue_lists_every_solver_with_typed_settings():
    specs = fcsolve.solvers()
    assert [s.name for s in specs] == SOLVER_NAMES
    for s in specs:
        assert s.family and s.summary and s.default_max_iter > 0
        assert fcsolve.solver(s.name) == s
        for setting in s.settings:
            assert setting.type in {"real", "integer", "boolean", "choice"} and setting.doc
            assert setting.default == fcsolve.Settings(s.name)[setting.name]
            assert (setting.type == "choice") == bool(setting.choices)
        assert s.name in fcsolve.solve.__doc__
    with pytest.raises(fcsolve.UsageError, match="unknown solver"):
        fcsolve.solver("no-such-solver")


def example_value(setting):
    """A valid value of the setting other than its default, if there is one."""
    if setting.type == "boolean":
        return not setting.default
    if setting.type == "choice":
        return next((c for c in setting.choices if c != setting.default), setting.default)
    if setting.type == "integer":
        return int(setting.default) + 1 if setting.default + 1 <= setting.max else int(setting.default)
    lo, hi = setting.min, setting.max
    if math.isfinite(lo) and math.isfinite(hi):
        return (lo + hi) / 2
    return setting.default


WRONG_TYPE = {"real": "1.0", "integer": 2.5, "boolean": 1, "choice": 3}


@pytest.mark.parametrize("solver", solver_params())
def test_settings_are_typed_and_checked(solver):
    spec = fcsolve.solver(solver)
    P = one_contact((-1.0, 0.1, 0.0), solver=solver)
    with pytest.raises(fcsolve.UsageError, match="unknown setting 'no_such_knob'"):
        fcsolve.solve(P, solver, no_such_knob=1)
    s = fcsolve.Settings(solver)
    with pytest.raises(ValueError):
        s.no_such_knob = 1
    with pytest.raises(AttributeError):
        s.no_such_knob
    for setting in spec.settings:
        with pytest.raises(TypeError, match=setting.name):
            fcsolve.solve(P, solver, **{setting.name: WRONG_TYPE[setting.type]})
        if setting.type == "choice":
            with pytest.raises(ValueError, match="not one of"):
                fcsolve.solve(P, solver, **{setting.name: "no-such-choice"})
        if setting.type in ("real", "integer") and math.isfinite(setting.max):
            with pytest.raises(ValueError, match="outside"):
                s[setting.name] = setting.max + 1
        value = example_value(setting)
        s[setting.name] = value
        assert s[setting.name] == value and getattr(s, setting.name) == value
        res = fcsolve.solve(P, solver, tol=1e-10, **{setting.name: value})
        assert res.error == pytest.approx(error_of(P, res), rel=1e-12, abs=1e-300)
    res = fcsolve.solve(P, s, tol=1e-10)  # a Settings object as the solver
    assert res.solver == solver
    assert s.as_dict() == dict(s.items()) and len(s) == len(spec.settings)
    assert repr(s).startswith(f"fcsolve.Settings('{solver}'")


def test_bad_solve_arguments():
    P = one_contact((-1.0, 0.1, 0.0))
    with pytest.raises(fcsolve.UsageError, match="unknown solver"):
        fcsolve.solve(P, "no-such-solver")
    with pytest.raises(TypeError):
        fcsolve.solve(P, 42)
    with pytest.raises(TypeError, match="LocalProblem"):
        fcsolve.solve({"W": 1})
    if not SOLVER_NAMES:
        pytest.skip("no solver is registered")
    name = SOLVER_NAMES[0]
    for bad in (0.0, -1e-8, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="tol"):
            fcsolve.solve(P, name, tol=bad)
    with pytest.raises(ValueError, match="max_iter"):
        fcsolve.solve(P, name, max_iter=0)
    with pytest.raises(TypeError, match="max_iter"):
        fcsolve.solve(P, name, max_iter=1.5)
    with pytest.raises(ValueError, match="max_time"):
        fcsolve.solve(P, name, max_time=0)
    with pytest.raises(TypeError, match="max_time"):
        fcsolve.solve(P, name, max_time="10")
    with pytest.raises(TypeError, match="callback"):
        fcsolve.solve(P, name, callback=3)
    with pytest.raises(ValueError, match="global"):
        fcsolve.solve(P, name, v0=np.zeros(3))
    with pytest.raises(fcsolve.InvalidProblemError) as e:
        fcsolve.solve(P, name, r0=np.zeros(4))
    assert e.value.field == "r0"
    with pytest.raises(fcsolve.InvalidProblemError):
        fcsolve.solve(P, name, r0=[np.nan, 0, 0])


@pytest.mark.parametrize("solver", solver_params())
def test_inputs_are_not_modified(solver):
    P = real_problem(solver, "FC3D_Example1.hdf5", "GFC3D_Example1.hdf5")
    names = ("M", "H", "f", "w", "mu") if isinstance(P, fcsolve.GlobalProblem) else ("W", "q", "mu")
    before = {n: getattr(P, n).copy() for n in names}
    r0 = np.full(P.size, 0.1)
    fcsolve.solve(P, solver, r0=r0)
    assert (r0 == 0.1).all()
    for n in names:
        after = getattr(P, n)
        if sp.issparse(after):
            assert (after != before[n]).nnz == 0, n
        else:
            assert (after == before[n]).all(), n


def test_result_fields():
    if not SOLVER_NAMES:
        pytest.skip("no solver is registered")
    G = fcsolve.load(data_file("GFC3D_Example1.hdf5"))
    res = fcsolve.solve(G, SOLVER_NAMES[0], tol=1e-8)
    assert res.v.shape == (G.num_dofs,) and res.multipliers is None
    assert res.seconds >= res.solve_seconds >= 0 and res.tol == 1e-8
    assert not res.r.flags.writeable
    assert isinstance(res.message, str) and res.status in repr(res)
    L = fcsolve.solve(one_contact((-1.0, 0.1, 0.0)), SOLVER_NAMES[0])
    assert L.v is None


# ---------------------------------------------------------------- GIL, Ctrl-C

def long_solver():
    """A local solver and problem that run until max_time at tol 1e-300."""
    if not SOLVER_NAMES:
        pytest.skip("no solver is registered")
    return local_solvers()[0], data_file("Capsules-i101-404.hdf5")


def test_gil_is_released_during_a_solve():
    solver, path = long_solver()
    P = fcsolve.load(path)
    done = threading.Event()
    results = []

    def work():
        results.append(fcsolve.solve(P, solver, tol=1e-300, max_iter=10**9, max_time=1.0))
        done.set()

    thread = threading.Thread(target=work)
    count, start = 0, time.perf_counter()
    thread.start()
    while not done.is_set():
        count += 1  # runs only while the solving thread does not hold the GIL
    thread.join()
    assert results[0].status == "timeout" and results[0].seconds >= 0.9
    # ~1 s of a Python loop: millions of turns if the GIL is free, a handful otherwise
    assert count > 10000, count


def test_ctrl_c_interrupts_a_long_solve():
    solver, path = long_solver()
    script = textwrap.dedent(f"""
        import sys, time, fcsolve
        P = fcsolve.load({str(path)!r})
        print("solving", flush=True)
        start = time.perf_counter()
        try:
            fcsolve.solve(P, {solver!r}, tol=1e-300, max_iter=10**9, max_time=30)
        except KeyboardInterrupt:
            print(f"interrupted after {{time.perf_counter() - start:.3f}}", flush=True)
            sys.exit(7)
        print("finished", flush=True)
    """)
    env = {"PYTHONPATH": str(Path(fcsolve.__file__).parents[1]), "OPENBLAS_NUM_THREADS": "1"}
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True, env=env)
    assert child.stdout.readline().strip() == "solving"
    time.sleep(0.5)
    sent = time.perf_counter()
    child.send_signal(signal.SIGINT)
    out, err = child.communicate(timeout=20)
    assert child.returncode == 7, (out, err)
    assert time.perf_counter() - sent < 5
    assert float(out.split()[-1]) < 10


@pytest.mark.parametrize("solver", ["nsgs", "auto", "nsn-ac-global"])
def test_global_error_scale_is_computed_once_per_problem(solver):
    """A GlobalProblem keeps ||H^T M^-1 f + w|| (the FCLIB error scale) from
    its first solve or error() and hands it to the next solves, which then do
    not factorise M for it: the reported errors must be those of a fresh
    problem and of fcref."""
    path = data_file("LMGC_GlobalFrictionContactProblem00046.hdf5")
    fresh = fcsolve.solve(fcsolve.load(path), solver, tol=1e-10)
    P = fcsolve.load(path)
    P.error(np.zeros(P.size))  # builds the scale first
    for _ in range(2):
        again = fcsolve.solve(P, solver, tol=1e-10)
        assert again.error == pytest.approx(fresh.error, rel=1e-12, abs=1e-300)
        assert again.error == pytest.approx(P.error(again.r, again.v), rel=1e-12, abs=1e-300)
        assert again.error == pytest.approx(reference_error(path, P, again.r, again.v), rel=1e-6, abs=1e-14)


def test_auto_callback_sees_every_iteration_when_a_stage_stops_crawling(tmp_path):
    """`auto` stops its interior-point stage through that stage's callback
    when it crawls; the caller's callback still sees every iteration of
    every stage, numbered 1..iterations, and the stop is not the caller's."""
    from campaign_support import real_cli

    cli = real_cli()
    if cli is None:
        pytest.skip("no built fcsolve CLI to generate the scene (FCSOLVE_CLI or build/fcsolve)")
    path = tmp_path / "stack-local.hdf5"
    g = subprocess.run([cli, "generate", "heavy-on-light", "--contacts", "3000", "--mass-ratio", "10000",
                        "--seed", "37", "--local-out", str(path)], capture_output=True, text=True, timeout=120)
    assert g.returncode == 0, g.stderr
    P = fcsolve.load(path)
    seen = []
    res = fcsolve.solve(P, "auto", tol=1e-8, max_time=60, callback=lambda i, e, s: seen.append(i))
    assert res.converged, res.message
    ipm = [st for st in res.stages if st["stage"] == "ipm"]
    assert ipm and "stopped crawling" in ipm[0]["why"], res.stages  # the scene's premise
    assert seen == list(range(1, res.iterations + 1))
    assert res.error == pytest.approx(reference_error(path, P, res.r), rel=1e-6, abs=1e-14)
