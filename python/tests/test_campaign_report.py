"""Campaign analysis and report (`fcsolve report`): performance profiles and
summaries on a hand-made CSV with known answers, the campaign's independent
error against shared/tools/fcref.py, problem families, the progress line,
and the charts and self-contained HTML page."""
import importlib.util
import io
import math
import re

import numpy as np
import pytest

from campaign_support import BUNDLED, FCREF, SHARED, campaign, real_cli, write_trivial_problem

from fcsolve.campaign import analysis, fclib_error, problems, progress, results

INF = math.inf


def hand_made_csv(out_dir):
    """3 problems x 3 solvers at tol 1e-8 (and one run at 1e-4):

        seconds (iterations)   P1          P2           P3
        A                      1   (10)    4   (40)     timeout
        B                      2   (5)     2   (20)     10  (100)
        C                      0.5 error 2e-8 > tol     -- (no row)  5 (50)
    """
    f = results.ResultsFile(str(out_dir))

    def run(problem, solver, seconds, iterations, error, failure, tol=1e-8):
        f.append(dict(problem=problem, kind="local", nc=1, m=3, solver=solver, tol=tol,
                      status=failure, seconds=seconds, iterations=iterations, own_error=error,
                      error=error, failure=failure, family=problem[:1], time_limit=20.0))

    run("P1", "A", 1.0, 10, 1e-9, "converged")
    run("P2", "A", 4.0, 40, 1e-9, "converged")
    run("P3", "A", 22.0, None, None, "timeout")
    run("P1", "B", 2.0, 5, 1e-9, "converged")
    run("P2", "B", 2.0, 20, 5e-9, "converged")
    run("P3", "B", 10.0, 100, 1e-10, "converged")
    run("P1", "C", 0.5, 3, 2e-8, "inaccurate")
    run("P3", "C", 5.0, 50, 1e-9, "converged")
    run("P1", "A", 0.5, 5, 1e-5, "converged", tol=1e-4)
    return results.load_results(str(out_dir))


def test_performance_profile_known_answer(tmp_path):
    rows = hand_made_csv(tmp_path)
    problems_, solvers, T = analysis.measure_table(rows, "seconds", 1e-8)
    assert problems_ == ["P1", "P2", "P3"] and solvers == ["A", "B", "C"]
    tau = analysis.performance_ratios(T)
    np.testing.assert_array_equal(tau, [[1, 2, INF], [2, 1, INF], [INF, 2, 1]])
    rho = analysis.profile(tau, [1, 1.5, 2, 100])
    np.testing.assert_allclose(rho, [[1 / 3, 1 / 3, 2 / 3, 2 / 3],
                                     [1 / 3, 1 / 3, 1.0, 1.0],
                                     [1 / 3, 1 / 3, 1 / 3, 1 / 3]])
    _, _, It = analysis.measure_table(rows, "iterations", 1e-8)
    np.testing.assert_array_equal(analysis.performance_ratios(It),
                                  [[2, 1, INF], [2, 1, INF], [INF, 2, 1]])
    # a problem nobody solved counts against everybody
    np.testing.assert_array_equal(analysis.performance_ratios(np.array([[INF, INF]])), [[INF, INF]])


def test_solved_means_recomputed_error_within_tol(tmp_path):
    rows = hand_made_csv(tmp_path)
    c_p1 = next(r for r in rows if r["solver"] == "C" and r["problem"] == "P1")
    assert c_p1["own_error"] == 2e-8 and not c_p1["solved"]
    assert results.solved(1e-8, 1e-8) and not results.solved(float("nan"), 1) \
        and not results.solved(None, 1)


def test_summary_and_work_precision(tmp_path):
    rows = hand_made_csv(tmp_path)
    s = {(e["solver"], e["tol"]): e for e in analysis.summary(rows)}
    a, b, c = s[("A", 1e-8)], s[("B", 1e-8)], s[("C", 1e-8)]
    assert (a["runs"], a["solved"], a["median_seconds"]) == (3, 2, 2.5)
    assert a["geomean_seconds"] == pytest.approx(2.0) and a["failures"] == {"converged": 2, "timeout": 1}
    assert b["solved_fraction"] == 1 and b["geomean_seconds"] == pytest.approx(40 ** (1 / 3))
    assert (c["runs"], c["solved"]) == (2, 1)
    fam = analysis.by_family(rows, 1e-8)
    assert fam == {"P": {"A": (2, 3), "B": (3, 3), "C": (1, 3)}}
    wp = analysis.work_precision(rows)
    # unsolved and missing runs count at the time limit (20 s), over all 3 problems
    assert wp["A"][1] == (1e-8, pytest.approx((1 * 4 * 20) ** (1 / 3)), pytest.approx(2 / 3))
    assert wp["C"][0] == (1e-8, pytest.approx((20 * 20 * 5) ** (1 / 3)), pytest.approx(1 / 3))
    assert wp["A"][0] == (1e-4, pytest.approx(0.5), 1.0)


def test_report_is_self_contained(tmp_path):
    rows = hand_made_csv(tmp_path)
    page = campaign.build_report(str(tmp_path))
    html = open(page).read()
    images = re.findall(r'<img [^>]*src="([^"]*)"', html)
    assert len(images) == 2 + 1 + 1 + 2  # profiles, work-precision, scatter, maps (2 tols)
    assert all(src.startswith("data:image/png;base64,") for src in images)
    assert "<table" in html and "P3" in html and "timeout" in html
    pngs = sorted(p.name for p in (tmp_path / "report").glob("*.png"))
    assert pngs == ["failure_map_tol0.0001.png", "failure_map_tol1e-08.png",
                    "profile_tol0.0001.png", "profile_tol1e-08.png", "time_vs_error.png",
                    "work_precision.png"]
    for p in (tmp_path / "report").glob("*.png"):
        data = p.read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10000
    assert len(rows) == 9


def _fcref():
    if not FCREF.is_file():
        pytest.skip("shared/tools/fcref.py absent")
    spec = importlib.util.spec_from_file_location("fcref", FCREF)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _files():
    found = sorted(BUNDLED.glob("*.hdf5")) + sorted(SHARED.glob("*/*.hdf5"))
    return list({p.name: p for p in found}.values())


def test_error_matches_fcref(tmp_path):
    """The campaign's own error agrees with the reference checker on every
    bundled and shared problem, for random r (and v), and on solutions
    returned by the binary (small errors, where cancellation would show)."""
    fcref = _fcref()
    rng = np.random.default_rng(7)
    checked = 0
    for path in _files():
        ref = fcref.load(str(path))
        if "G" in ref:
            continue  # fcref does not handle bilateral constraints
        mine = fclib_error.load_problem(str(path))
        m = mine.m
        for scale in (1.0, 1e-6):
            r = scale * rng.standard_normal(m)
            if mine.kind == "local":
                assert fclib_error.error(mine, r) == pytest.approx(fcref.error(ref, r), rel=1e-10)
            else:
                v = rng.standard_normal(mine.n)
                assert fclib_error.error(mine, r, v) == pytest.approx(fcref.error(ref, r, v), rel=1e-9)
                assert fclib_error.error(mine, r) == pytest.approx(fcref.error(ref, r), rel=1e-7)
        checked += 1
    assert checked >= 10
    if real_cli():
        import subprocess

        for name in ("Capsules-i101-404", "Box_Stacks-i0035-31-0"):
            sol = tmp_path / f"{name}.sol.hdf5"
            subprocess.run([real_cli(), "solve", str(BUNDLED / f"{name}.hdf5"), "--solver", "vi-fp",
                            "--tol", "1e-9", "--out", str(sol)], capture_output=True, timeout=120)
            r, v, _ = fclib_error.read_solution(str(sol))
            mine = fclib_error.solution_error(str(BUNDLED / f"{name}.hdf5"), str(sol))
            ref = fcref.error(fcref.load(str(BUNDLED / f"{name}.hdf5")), r, v)
            assert ref < 1e-6 and mine == pytest.approx(ref, rel=1e-8)
    trivial = fclib_error.Problem(write_trivial_problem(tmp_path / "t.hdf5"))
    assert fclib_error.error(trivial, np.zeros(6)) == 0.0
    assert math.isnan(fclib_error.error(trivial, np.full(6, np.nan)))


def test_families_from_file_names():
    expected = {
        "Capsules-i101-404": "Capsules", "Rover1039": "Rover", "BoxesStack1-i100000-32": "BoxesStack",
        "LMGC_GlobalFrictionContactProblem00046": "LMGC", "LMGC_100_PR_PerioBox-i00361-60-03000": "LMGC",
        "Box_Stacks-i0035-31-0": "Box_Stacks", "CubeH8": "CubeH8", "Cubes_H8_2-i0001": "Cubes_H8",
        "NESpheres_10_1": "NESpheres", "FC3D_Example1": "FC3D_Example", "945_SP_Box_PL-i00001": "945_SP_Box_PL",
        "KaplasTower-i1000-412": "KaplasTower", "OneObject-i1028-138": "OneObject",
        "local/Rover4396": "Rover",
    }
    assert {n: problems.problem_family(n) for n in expected} == expected
    assert problems.problem_names(["a/x.hdf5", "b/x.hdf5", "b/y.hdf5"]) == ["a/x", "b/x", "y"]


def test_progress_line_with_eta_when_not_a_tty():
    now = [0.0]
    stream = io.StringIO()
    p = progress.Progress(4, stream=stream, clock=lambda: now[0])
    now[0] = 10.0
    p.update(dict(problem="P1", solver="A", tol=1e-8, failure="converged"))
    line = stream.getvalue().splitlines()[-1]
    assert "1/4" in line and "25%" in line and "eta 00:30" in line and "P1 A tol=1e-08" in line
    assert "\r" not in stream.getvalue()
