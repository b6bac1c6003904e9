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
    # family view (3) + profiles, work-precision, scatter, maps (2 tols)
    assert len(images) == 3 + 2 + 1 + 1 + 2
    assert all(src.startswith("data:image/png;base64,") for src in images)
    assert "<table" in html and "P3" in html and "timeout" in html
    pngs = sorted(p.name for p in (tmp_path / "report").glob("*.png"))
    assert pngs == ["failure_map_tol0.0001.png", "failure_map_tol1e-08.png",
                    "family_failure_map_tol1e-08.png", "family_profile.png", "family_work_precision.png",
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


# ---------------------------------------------------------------- family view

def synthetic_rows(runs, tols=(1e-4, 1e-8), problems=("P1", "P2", "P3")):
    """Typed rows without a CSV. runs: {solver: {(problem, tol): seconds}};
    a run listed is solved, every other (problem, tol) is a timeout."""
    rows = []
    for solver, solved_runs in runs.items():
        for p in problems:
            for tol in tols:
                t = solved_runs.get((p, tol))
                rows.append(dict(problem=p, solver=solver, tol=tol, family="Q",
                                 seconds=t if t is not None else 10.0, iterations=1,
                                 failure="converged" if t is not None else "timeout",
                                 solved=t is not None, time_limit=10.0))
    return rows


def everywhere(seconds, problems=("P1", "P2", "P3"), tols=(1e-4, 1e-8)):
    return {(p, t): seconds for p in problems for t in tols}


def test_best_member_most_solved_at_tightest_tol_then_least_time():
    rows = synthetic_rows({
        # x solves 2 at 1e-8 in 5 s, y 2 in 3 s: y; z solves all at 1e-4 only
        "x": {("P1", 1e-8): 1.0, ("P2", 1e-8): 4.0},
        "y": {("P1", 1e-8): 2.0, ("P3", 1e-8): 1.0},
        "z": everywhere(0.1, tols=(1e-4,)),
        # equal count and time: the name decides, whatever the row order
        "w2": {("P1", 1e-8): 1.0}, "w1": {("P2", 1e-8): 1.0},
        "siconos:nsgs": {("P1", 1e-8): 1.0}, "siconos:nsn-ac": everywhere(9.0),
    })
    families = {"x": "f", "y": "f", "z": "f", "w2": "g", "w1": "g"}
    best = analysis.best_members(rows, families)
    assert best == {"f": "y", "g": "w1", "siconos": "siconos:nsn-ac"}
    assert analysis.solved_and_time(rows, "y", 1e-8) == (2, 3.0)
    # without recorded families, a solver is its own family, a peer its peer
    assert analysis.family_of_solver("nsgs") == "nsgs"
    assert analysis.family_of_solver("siconos:prox") == "siconos"


def test_family_lines_at_most_eight_auto_always_kept():
    # 11 families; family k's only member solves k problems... auto solves none
    problems = tuple(f"P{k}" for k in range(12))
    runs = {f"s{k}": {(p, 1e-8): 1.0 + k for p in problems[:k]} for k in range(1, 11)}
    runs["auto"] = {}
    families = {f"s{k}": f"fam{k}" for k in range(1, 11)}
    families["auto"] = "auto"
    rows = synthetic_rows(runs, tols=(1e-8,), problems=problems)
    lines, left_out = analysis.family_lines(rows, families)
    assert len(lines) == 8 and lines[0] == ("auto", "auto")
    assert [f for f, _ in lines[1:]] == [f"fam{k}" for k in range(10, 3, -1)]
    assert left_out == ["fam3", "fam2", "fam1"]
    few, none_left = analysis.family_lines(rows, families, max_lines=20)
    assert len(few) == 11 and none_left == []
    # no auto in the campaign: 8 best families
    no_auto = [r for r in rows if r["solver"] != "auto"]
    lines, left_out = analysis.family_lines(no_auto, families)
    assert len(lines) == 8 and ("auto", "auto") not in lines and len(left_out) == 2


def test_family_colours_stable_and_distinct():
    from fcsolve.campaign import charts

    a = charts.family_styles([("auto", "auto"), ("nsgs", "nsgs-ac"), ("newton", "nsn-ac"),
                              ("siconos", "siconos:nsn-ac")], peers={"siconos"})
    b = charts.family_styles([("newton", "nsn-fb"), ("nsgs", "psor"), ("siconos", "siconos:nsgs"),
                              ("vi", "vi-eg")], peers={"siconos"})
    assert a["nsgs-ac"]["color"] == b["psor"]["color"] == charts.family_colour("nsgs")
    assert a["nsn-ac"]["color"] == b["nsn-fb"]["color"]
    assert a["siconos:nsn-ac"]["linestyle"] == "--" and a["nsgs-ac"]["linestyle"] == "-"
    assert a["auto"]["color"] == "#000000" and a["auto"]["linewidth"] > a["nsgs-ac"]["linewidth"]
    known = list(charts.FAMILY_COLOURS)
    assert len({charts.family_colour(f) for f in known}) == len(known)
    assert charts.family_colour("someday") == charts.family_colour("someday")
    assert a["nsn-ac"]["label"] == "newton: nsn-ac" and a["auto"]["label"] == "auto"
    assert a["siconos:nsn-ac"]["label"] == "siconos:nsn-ac"


def test_family_view_profiles_keep_every_problem(tmp_path):
    rows = synthetic_rows({"a": {("P1", 1e-8): 1.0}, "b": {("P1", 1e-8): 2.0, ("P2", 1e-8): 1.0},
                           "c": everywhere(0.5)})
    problems_, solvers, T = analysis.measure_table(rows, "seconds", 1e-8, ["a", "b"])
    assert problems_ == ["P1", "P2", "P3"] and solvers == ["a", "b"]
    np.testing.assert_array_equal(analysis.performance_ratios(T), [[1, 2], [INF, 1], [INF, INF]])
    wp = analysis.work_precision(rows, ["b", "a"])
    assert list(wp) == ["b", "a"] and wp["a"][1][2] == pytest.approx(1 / 3)


def test_report_family_view_uses_recorded_families(tmp_path):
    import json

    hand_made_csv(tmp_path)
    solvers = [dict(name="A", family="nsgs", peer=False), dict(name="B", family="nsgs", peer=False),
               dict(name="C", family="auto", peer=False)]
    (tmp_path / "campaign.json").write_text(json.dumps(dict(invocations=[dict(solvers=solvers)])))
    html = open(campaign.build_report(str(tmp_path))).read()
    # B solves 3 at 1e-8, A 2: B is nsgs' best member; C is auto
    section = html[html.index("Family view"):html.index("Summary per solver")]
    assert re.search(r"nsgs</td><td>B</td><td>3</td>", section)
    assert re.search(r"auto</td><td>C</td><td>1</td>", section)
    assert "left out" not in section.replace("<b>left out</b>", "")
