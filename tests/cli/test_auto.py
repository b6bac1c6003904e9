"""End-to-end checks of `auto`, the default solver of `fcsolve solve FILE`:
it solves the bundled problems (and, when ../shared is beside the checkout,
every shared one) to the tolerance by the independent reference
shared/tools/fcref.py; it reports its stages in the JSON output and the
message; it honours --max-time without claiming a false convergence; and it
is deterministic for a given input and settings."""
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
SHARED = Path(os.environ.get("FCSOLVE_SHARED_DATA", ROOT.parent / "shared" / "data" / "fclib"))
TOOLS = SHARED.parent.parent / "tools"
BUNDLED = ROOT / "examples" / "data"
CLI = os.environ.get("FCSOLVE_CLI", str(ROOT / "build" / "fcsolve"))

have_fcref = (TOOLS / "fcref.py").is_file()
have_shared = (SHARED / "local").is_dir() and have_fcref
needs_shared = pytest.mark.skipif(not have_shared, reason="../shared (FCLIB collection, fcref.py) absent")

if have_fcref:
    sys.path.insert(0, str(TOOLS))
    import fcref  # noqa: E402  the independent reference, used only to check

STAGE_KEYS = {"stage", "solver", "seconds", "iterations", "error", "status", "why"}


def run(*args, timeout=120):
    p = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, timeout=timeout)
    assert p.returncode >= 0, f"fcsolve died from signal {-p.returncode}: {p.stderr}"
    return p


def solve_json(problem, *options, out=None):
    args = ["solve", problem, "--json", *options]
    if out is not None:
        args += ["--out", out]
    p = run(*args)
    assert p.returncode in (0, 1), p.stderr
    return p.returncode, json.loads(p.stdout)


def solution(path):
    with h5py.File(path) as f:
        r = np.asarray(f["solution/r"])
        v = np.asarray(f["solution/v"]) if "solution/v" in f else None
    return r, v


def independent_error(problem, sol_file):
    """fcref's error when the reference is beside the checkout, else the
    CLI's own `fcsolve error` (the same formula, recomputed from the file)."""
    r, v = solution(sol_file)
    if have_fcref:
        return fcref.error(fcref.load(str(problem)), r, v)
    p = run("error", problem, sol_file, "--json")
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)["error"]


def bundled_files():
    return sorted(BUNDLED.glob("*.hdf5"))


def check_stages(res):
    assert res["solver"] == "auto"
    assert isinstance(res["stages"], list) and res["stages"], res
    for st in res["stages"]:
        assert STAGE_KEYS <= set(st), st
        assert st["why"], st
    assert sum(st["iterations"] for st in res["stages"]) == res["iterations"]
    assert "stages [" in res["message"]
    # the result is the best iterate a stage reached (stages of a global
    # problem measure on its reduction: equal up to round-off)
    errors = [st["error"] for st in res["stages"] if st["error"] is not None]
    assert res["error"] <= min(errors) * (1 + 1e-6) + 1e-12
    check_no_newton_stage_repeats_a_stall(res["stages"])
    check_sweeps_matching_the_interior_point(res["stages"])
    check_singular_route(res)


SINGULAR_CONTACT_RATIO = 1.1  # kSingularContactRatio in auto_entries.hpp


def contact_ratio(res):
    """d nc / n of an FC/I run, from the features in its message (None: FC/II)."""
    m = re.search(r"d\*nc/n=([0-9.eE+-]+)", res["message"])
    return float(m.group(1)) if m else None


def check_singular_route(res):
    """Only FC/I with d nc / n above kSingularContactRatio goes from the
    warm sweeps straight to Newton ("W singular"); FC/II, whose ratio the
    plan does not know, and FC/I at or below it (sphere piles: 1.00 to
    1.01) go through the sweeps' chunks."""
    if not any("W singular" in st["why"] for st in res["stages"]):
        return
    ratio = contact_ratio(res)
    assert ratio is not None and ratio > SINGULAR_CONTACT_RATIO, res["message"]


def check_no_newton_stage_repeats_a_stall(stages):
    """A Newton stage is deterministic: once it stalled, it must not run
    again until the best error is at most half of the one it started from
    (kNewtonRestartGain in auto_entries.hpp)."""
    stalled_from = {}
    best = float("inf")
    for st in stages:
        if st["stage"] in ("newton-full", "newton"):
            assert not best > 0.5 * stalled_from.get(st["stage"], float("inf")), \
                f"{st['stage']} again from an iterate not twice as good: {stages}"
            if st["status"] == "stalled":
                stalled_from[st["stage"]] = best
        if st["error"] is not None:
            best = min(best, st["error"])


def check_sweeps_matching_the_interior_point(stages):
    """Sweeps get the interior point's time back only right after an
    interior point that did not halve the best error (kInteriorPointGain in
    auto_entries.hpp), and run no longer than it did (plus one sweep's
    overshoot of the clock)."""
    for k, st in enumerate(stages):
        if st["why"].startswith("the interior point gained less than"):
            ipm = stages[k - 1]
            assert st["stage"] == "nsgs" and ipm["stage"] == "ipm", stages
            before = min(s["error"] for s in stages[:k - 1] if s["error"] is not None)
            assert ipm["error"] is None or not ipm["error"] * 2 <= before, stages
            assert st["seconds"] <= 1.1 * ipm["seconds"] + 0.05, stages


@pytest.mark.parametrize("problem", bundled_files(), ids=lambda p: p.name)
def test_auto_is_the_default_and_solves_bundled_problems(problem, tmp_path):
    sol = tmp_path / "sol.hdf5"
    code, res = solve_json(problem, "--max-time", 20, out=sol)  # no --solver: auto
    assert code == 0 and res["status"] == "converged", res
    assert res["error"] <= 1e-8
    check_stages(res)
    assert independent_error(problem, sol) <= 1e-8
    if res["kind"] == "global":
        assert solution(sol)[1] is not None  # v recovered


@needs_shared
@pytest.mark.parametrize("problem", sorted(SHARED.glob("*/*.hdf5")) if have_shared else [],
                         ids=lambda p: p.name)
def test_auto_solves_every_shared_problem(problem, tmp_path):
    sol = tmp_path / "sol.hdf5"
    code, res = solve_json(problem, "--max-time", 20, out=sol)
    assert code == 0 and res["status"] == "converged", res
    assert fcref.error(fcref.load(str(problem)), *solution(sol)) <= 1e-8


def test_max_time_is_honoured_without_a_false_convergence(tmp_path):
    # 1e-30 is below round-off: no stage converges; the run ends when the
    # budget is spent or, at round-off, when its last sweeps stop on their
    # plateau (stalled).
    problem = BUNDLED / "Capsules-i101-404.hdf5"
    sol = tmp_path / "sol.hdf5"
    code, res = solve_json(problem, "--tol", "1e-30", "--max-time", 0.5, out=sol)
    assert code == 1 and res["status"] in ("timeout", "stalled") and not res["converged"], res
    if res["status"] == "stalled":
        last = res["stages"][-1]
        assert last["solver"] == "nsgs" and last["status"] == "stalled", last
    # a generous bound (a loaded machine): the budget cuts the run, not an iteration cap
    assert res["seconds"] < 5, res
    check_stages(res)
    err = independent_error(problem, sol)
    assert err == pytest.approx(res["error"], rel=1e-8)
    assert err < 1e-6  # still the best iterate of its stages, not the start


@pytest.mark.parametrize("name", ["Capsules-i101-404.hdf5", "Box_Stacks-i0035-31-0.hdf5"])
def test_deterministic(name, tmp_path):
    problem = BUNDLED / name
    runs = []
    for k in range(2):
        sol = tmp_path / f"sol{k}.hdf5"
        _, res = solve_json(problem, "--tol", "1e-10", "--max-time", 20, out=sol)
        runs.append((res, solution(sol)))
    (a, (ra, va)), (b, (rb, vb)) = runs
    assert np.array_equal(ra, rb)
    assert (va is None and vb is None) or np.array_equal(va, vb)
    assert [(s["solver"], s["iterations"], s["why"]) for s in a["stages"]] == \
           [(s["solver"], s["iterations"], s["why"]) for s in b["stages"]]
    assert a["error"] == b["error"]


@pytest.mark.parametrize("scene, after", [
    # mass ratio 100 between stacked boxes (W_NN spread ~110), and 1000 on
    # 12 contacts (spread ~2): Newton's full steps stall, and the interior
    # point runs next and ends the plan (before the line search, the bridge
    # sweeps and a second Newton)
    (["--contacts", 300, "--seed", 40, "--mu", 2, "--mass-ratio", 100,
      "--penetration-correction", 0.2], ["nsgs", "newton-full"]),
    (["--contacts", 10, "--seed", 34], ["nsgs", "newton-full"]),
], ids=["mass-ratio-100", "mass-ratio-1000"])
def test_interior_point_stage_on_heavy_on_light_stacks(scene, after, tmp_path):
    local = tmp_path / "stack-local.hdf5"
    g = run("generate", "heavy-on-light", *scene, "--local-out", local)
    assert g.returncode == 0, g.stderr
    sol = tmp_path / "sol.hdf5"
    code, res = solve_json(local, "--max-time", 20, out=sol)
    assert code == 0 and res["status"] == "converged", res
    check_stages(res)
    assert [st["stage"] for st in res["stages"]] == after + ["ipm"], res["message"]
    assert independent_error(local, sol) <= 1e-8


def test_full_newton_steps_that_stall_near_tol_are_finished_by_sweeps(tmp_path):
    # a running-bond wall of 600 contacts given as FC/II (mu 1, top row 10x
    # denser; W singular): full Newton steps bring the error from 0.5 to
    # about 1e-8, then hover between 1e-8 and 3e-8 while a few degenerate
    # contacts change sides, and stall. Stalled within 10 x tol after
    # lowering the error 1000x or more, they hand over to 50 sweeps before
    # the interior point, and the sweeps finish: no interior point
    local = tmp_path / "wall-local.hdf5"
    g = run("generate", "wall", "--contacts", 600, "--seed", 901, "--mu", 1, "--mass-ratio", 10,
            "--local-out", local)
    assert g.returncode == 0, g.stderr
    sol = tmp_path / "sol.hdf5"
    code, res = solve_json(local, "--max-time", 60, out=sol)
    assert code == 0 and res["status"] == "converged", res["message"]
    check_stages(res)
    stages = res["stages"]
    k = next(k for k, st in enumerate(stages) if st["stage"] == "newton-full")
    if stages[k]["status"] == "converged":
        # Round-off decides whether the steps hover above tol and stall (the
        # 2-core AMD EPYC this was written on) or land below it (a 2-core
        # Intel Xeon, 2026-12-07, old and new binaries alike: 54-56 steps to
        # 5e-9 to 9e-9): then there is nothing to hand over, the run ends there.
        assert k == len(stages) - 1, res["message"]
        assert independent_error(local, sol) <= 1e-8
        return
    assert stages[k]["status"] == "stalled" and 1e-8 < stages[k]["error"] <= 1e-7, res["message"]  # the premise
    assert stages[k + 1]["stage"] == "nsgs" and "x tol" in stages[k + 1]["why"], res["message"]
    assert stages[k + 1]["iterations"] <= 50 and k + 1 == len(stages) - 1, res["message"]
    assert independent_error(local, sol) <= 1e-8


ON_FC1 = {"ipm-socqp", "nsn-ac-global"}  # stages that run on FC/I when its linear algebra is cheaper


@pytest.mark.parametrize("scene, seed, fc1_stages", [
    # Kapla towers: ~20 contacts per plank, nnz(W) ~16x nnz(H) + nnz(M):
    # every contact sticks, and the sticking probe (the convex associated
    # problem, by an interior point on FC/I) solves it
    ("tower", 5, {"ipm-socqp"}),
    # a wall where some contact slides: the probe stalls, sweeps, and
    # Newton runs on FC/I in (v, r)
    ("wall", 19, {"ipm-socqp", "nsn-ac-global"}),
    # columns of cubes: nnz(W) ~5x, W's factorisation costs no more: on W
    ("box-stack", 5, set()),
])
def test_stages_run_on_the_cheaper_form_of_a_rigid_fc1(scene, seed, fc1_stages, tmp_path):
    problem, local = tmp_path / "scene.hdf5", tmp_path / "scene-local.hdf5"
    g = run("generate", scene, "--contacts", 100, "--seed", seed, "--out", problem, "--local-out", local)
    assert g.returncode == 0, g.stderr
    sol = tmp_path / "sol.hdf5"
    code, res = solve_json(problem, "--max-time", 20, out=sol)
    assert code == 0 and res["status"] == "converged", res
    check_stages(res)
    solvers = [st["solver"] for st in res["stages"]]
    assert ON_FC1 & set(solvers) == fc1_stages, res["message"]
    if fc1_stages:
        assert solvers[0] == "ipm-socqp", res["message"]
    else:
        assert "nsn-ac" in solvers, res["message"]
    assert independent_error(problem, sol) <= 1e-8
    # the same scene given as FC/II has only W
    code, res = solve_json(local, "--max-time", 20, out=sol)
    assert code == 0 and res["status"] == "converged", res
    assert not ON_FC1 & {st["solver"] for st in res["stages"]}, res["message"]
    assert independent_error(local, sol) <= 1e-8


def test_text_output_names_the_stages():
    p = run("solve", BUNDLED / "OneObject-i1028-138.hdf5")
    assert p.returncode == 0, p.stderr
    assert "solver=auto" in p.stdout and "status=converged" in p.stdout
    assert "stages [" in p.stdout


def test_auto_listed_among_the_solvers():
    p = run("solvers", "--json")
    names = {e["name"]: e for e in json.loads(p.stdout)}
    assert "auto" in names and names["auto"]["local"] and names["auto"]["global_native"]


def solved_heavy_on_light_stack(tmp_path, *scene):
    """A heavy-on-light stack of 300 contacts, mass ratio 1e4, as FC/II, solved
    by `auto` (converged, stages well-formed): (problem, solution, JSON)."""
    local = tmp_path / "stack-local.hdf5"
    g = run("generate", "heavy-on-light", "--contacts", 300, "--mass-ratio", 10000, *scene,
            "--local-out", local)
    assert g.returncode == 0, g.stderr
    sol = tmp_path / "sol.hdf5"
    code, res = solve_json(local, "--max-time", 20, out=sol)
    assert code == 0 and res["status"] == "converged", res
    check_stages(res)
    return local, sol, res


def test_frictionless_scene_gets_the_interior_point_when_full_newton_steps_stall(tmp_path):
    # frictionless heavy-on-light stack, mass ratio 1e4: full Newton steps
    # stall; the interior point handles mu = 0 (its Lorentz block without
    # the tangential part) and solves it, before any line search
    local, sol, res = solved_heavy_on_light_stack(tmp_path, "--seed", 39, "--mu", 0)
    names = [st["stage"] for st in res["stages"]]
    assert "ipm" in names, res["message"]
    assert "newton" not in names, res["message"]  # no line-searched Newton was needed
    assert independent_error(local, sol) <= 1e-8


def test_bridge_sweeps_stop_after_a_first_chunk_that_does_not_help(tmp_path):
    # heavy-on-light stack, mu = 1, mass ratio 1e4, penetration correction:
    # full and line-searched Newton steps stall on either side of the
    # interior point, and sweeps from Newton's iterate do not lower the
    # error: the bridge stops after its first chunk and Newton runs again
    local, sol, res = solved_heavy_on_light_stack(tmp_path, "--seed", 41, "--mu", 1,
                                                  "--penetration-correction", 0.5)
    stages = res["stages"]
    bridge = next(k for k in range(1, len(stages))
                  if stages[k]["stage"] == "nsgs" and stages[k - 1]["stage"].startswith("newton"))
    assert stages[bridge]["iterations"] <= 50, res["message"]
    best_before = min(st["error"] for st in stages[:bridge])
    assert stages[bridge]["error"] >= best_before, res["message"]  # the scene's premise
    assert stages[bridge + 1]["stage"].startswith("newton"), res["message"]
    assert independent_error(local, sol) <= 1e-8


def solved_sphere_pile(tmp_path, contacts, seed, tol):
    """A generated sphere pile (FC/II) solved by `auto` to tol (converged,
    stages well-formed, independent error within tol): the JSON's stages."""
    local = tmp_path / "pile-local.hdf5"
    g = run("generate", "sphere-pile", "--contacts", contacts, "--seed", seed, "--local-out", local)
    assert g.returncode == 0, g.stderr
    sol = tmp_path / "sol.hdf5"
    code, res = solve_json(local, "--tol", tol, "--max-time", 60, out=sol)
    assert code == 0 and res["status"] == "converged", res["message"]
    check_stages(res)
    assert independent_error(local, sol) <= tol
    return res["stages"]


def resumed_sweeps(stages):
    """The index of the sweeps resumed after full Newton steps that did not
    lower the error, checked against that premise."""
    k = next(k for k, st in enumerate(stages) if st["why"].startswith("full Newton steps made no progress"))
    assert stages[k]["stage"] == "nsgs"
    assert stages[k - 1]["stage"] == "newton-full"
    assert stages[k - 1]["error"] >= min(st["error"] for st in stages[:k - 1])  # no progress
    return k


def test_sweeps_resume_when_full_newton_steps_make_no_progress(tmp_path):
    # a sphere pile of 10^4 contacts at 1e-4: the sweeps' rate predicts more
    # than three Newton steps' cost, full steps stall on the pile (W
    # singular), and the sweeps, resumed with the interior point's allowance,
    # finish: no interior-point, line-search or proximal stage runs
    stages = solved_sphere_pile(tmp_path, 10000, 5, 1e-4)
    k = resumed_sweeps(stages)
    assert all(st["stage"] == "nsgs" for st in stages[k:]), stages
    assert stages[-1]["status"] == "converged"


def test_a_newton_stage_is_not_repeated_from_the_iterate_it_stalled_from(tmp_path):
    # a sphere pile of 3000 contacts at 1e-8: the line search stalls from
    # the interior point's iterate, and neither the bridge's sweeps nor the
    # full steps after them improve it; the plan goes on to the proximal
    # stage without running the line search again from there
    # (check_stages checks the rule, solved_sphere_pile calls it)
    stages = solved_sphere_pile(tmp_path, 3000, 4, 1e-8)
    assert [st["stage"] for st in stages].count("newton") == 1, stages
    assert stages[-1]["stage"] == "proximal", stages


def test_resumed_sweeps_stop_at_a_plateau(tmp_path):
    # a sphere pile of 1000 contacts at 1e-4: Gauss-Seidel stalls near
    # 1.1e-4; the resumed sweeps stop when a chunk's rate is four times
    # slower than the chunk's before, and the interior point finishes
    stages = solved_sphere_pile(tmp_path, 1000, 3, 1e-4)
    k = resumed_sweeps(stages)
    nxt = next(j for j in range(k, len(stages)) if stages[j]["stage"] != "nsgs")
    assert stages[nxt]["stage"] == "ipm" and "a plateau" in stages[nxt]["why"], stages
    assert sum(st["iterations"] for st in stages[k:nxt]) <= 1000


def test_sweeps_get_the_time_of_an_interior_point_that_did_not_pay(tmp_path):
    # a sphere pile of 3000 contacts (seed 911) at 1e-8: full Newton steps
    # stall, the resumed sweeps stop on what looks like a plateau (1e-3), the
    # interior point runs its 100 iterations without lowering the error; the
    # sweeps, still lowering it, get its time back (about 23 000 sweeps to
    # 1.6e-5 on an Intel Xeon) and the run converges from their iterate
    # (before the rule: the proximal stage, after 29 s)
    stages = solved_sphere_pile(tmp_path, 3000, 911, 1e-8)
    k = next(k for k, st in enumerate(stages) if st["why"].startswith("the interior point gained less than"))
    assert stages[k - 1]["stage"] == "ipm", stages
    before = min(st["error"] for st in stages[:k - 1])
    assert stages[k]["error"] < 0.5 * before, stages  # the sweeps paid


def test_sphere_pile_as_fc1_goes_through_the_sweeps_chunks(tmp_path):
    # a sphere pile has two contacts a sphere: d nc / n = 1.01 here, W nearly
    # of full rank. Given as FC/I it goes through the sweeps' chunks before
    # Newton, as its FC/II form does (before: straight to Newton, "W
    # singular"); a box stack (d nc / n = 2) still takes that route
    pile = tmp_path / "pile.hdf5"
    g = run("generate", "sphere-pile", "--contacts", 300, "--seed", 941, "--out", pile)
    assert g.returncode == 0, g.stderr
    sol = tmp_path / "sol.hdf5"
    code, res = solve_json(pile, out=sol)
    assert code == 0 and res["status"] == "converged", res["message"]
    check_stages(res)
    ratio = contact_ratio(res)
    assert ratio is not None and 1 <= ratio <= SINGULAR_CONTACT_RATIO, res["message"]  # the premise
    stages = res["stages"]
    k = next(k for k, st in enumerate(stages) if st["stage"] == "newton-full")
    assert any("predicts" in st["why"] for st in stages[:k]), res["message"]
    assert independent_error(pile, sol) <= 1e-8
    stack = tmp_path / "stack.hdf5"
    g = run("generate", "box-stack", "--contacts", 200, "--seed", 941, "--out", stack)
    assert g.returncode == 0, g.stderr
    code, res = solve_json(stack)
    check_stages(res)
    assert any("W singular" in st["why"] for st in res["stages"]), res["message"]


def test_interior_point_stage_stops_when_it_crawls(tmp_path):
    # a heavy-on-light stack of 3000 contacts (mass ratio 1e4) at 1e-8: full
    # Newton steps stall; the interior point's error falls to about 2e-5,
    # then by under 1 % in 12 iterations: the stage stops there, well short
    # of its 100 iterations, and Newton converges from its iterate
    local = tmp_path / "stack-local.hdf5"
    g = run("generate", "heavy-on-light", "--contacts", 3000, "--mass-ratio", 10000, "--seed", 37,
            "--local-out", local)
    assert g.returncode == 0, g.stderr
    sol = tmp_path / "sol.hdf5"
    code, res = solve_json(local, "--tol", 1e-8, "--max-time", 60, out=sol)
    assert code == 0 and res["status"] == "converged", res["message"]
    check_stages(res)
    assert independent_error(local, sol) <= 1e-8
    stages = res["stages"]
    k = next(k for k, st in enumerate(stages) if st["stage"] == "ipm")
    ipm = stages[k]
    assert ipm["status"] == "stalled" and "stopped crawling" in ipm["why"], stages
    assert ipm["iterations"] < 100, stages
    assert ipm["error"] < min(st["error"] for st in stages[:k]), stages  # a better iterate
    assert stages[k + 1]["stage"].startswith("newton") and stages[-1]["status"] == "converged", stages
