"""`fcsolve generate`: a small instance of every scene is valid FCLIB (read
back by `fcsolve info` and by the independent shared/tools/fcref.py), FC/I
and its FC/II reduction agree, a solver solves it to 1e-8 as fcref measures
it, the scene parameters are in the info strings, the same seed gives the
same file, and bad options exit 2 with a message."""
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
CLI = os.environ.get("FCSOLVE_CLI", str(ROOT / "build" / "fcsolve"))

have_fcref = (TOOLS / "fcref.py").is_file()
needs_fcref = pytest.mark.skipif(not have_fcref, reason="../shared/tools/fcref.py absent (lone clone)")
if have_fcref:
    sys.path.insert(0, str(TOOLS))
    import fcref  # noqa: E402  the independent reference, used only to check

SCENES = ["sphere-pile", "box-stack", "wall", "tower", "mixed-shapes", "heavy-on-light", "fem-block",
          "fem-two-bodies"]
TOL = 1e-8


def run(*args, timeout=120):
    p = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, timeout=timeout)
    assert p.returncode >= 0, f"fcsolve died from signal {-p.returncode}: {p.stderr}"
    return p


def fields(line):
    return dict(kv.split("=", 1) for kv in line.split() if "=" in kv)


def generate(tmp_path, scene, *extra, contacts=10):
    out, local = tmp_path / f"{scene}.hdf5", tmp_path / f"{scene}-local.hdf5"
    p = run("generate", scene, "--contacts", contacts, "--out", out, "--local-out", local, *extra)
    assert p.returncode == 0, p.stderr
    return out, local, fields(p.stdout)


def solve_and_recheck(path, tmp_path):
    """`fcsolve solve` (auto) reaches TOL and fcref agrees on the error."""
    sol = tmp_path / (Path(path).stem + "-sol.hdf5")
    p = run("solve", path, "--tol", TOL, "--out", sol, "--json")
    assert p.returncode == 0, (p.stdout, p.stderr)
    assert json.loads(p.stdout)["error"] <= TOL
    with h5py.File(sol, "r") as f:
        r = f["solution/r"][()]
        v = f["solution/v"][()] if "solution/v" in f else None
    ref = fcref.load(str(path))
    assert fcref.error(ref, r, v if ref["kind"] == "global" else None) <= TOL


@needs_fcref
@pytest.mark.parametrize("scene", SCENES)
def test_every_scene_is_valid_fclib_and_solvable(tmp_path, scene):
    out, local, gen = generate(tmp_path, scene)
    nc = int(gen["nc"])
    assert 4 <= nc <= 30, gen  # about the 10 asked for
    for path, kind in ((out, "global"), (local, "local")):
        info = json.loads(run("info", path, "--json").stdout)
        assert (info["kind"], info["nc"], info["d"]) == (kind, nc, 3)
        ref = fcref.load(str(path))
        assert ref["kind"] == kind and ref["mu"].size == nc and ref["d"] == 3
        assert np.all(ref["mu"] == 0.5)
        solve_and_recheck(path, tmp_path)
        # the scene parameters are recorded in the FCLIB info strings
        with h5py.File(path, "r") as f:
            group = f["fclib_global" if kind == "global" else "fclib_local"]
            text = " ".join(str(group["info"][k][()]) for k in ("title", "description", "math_info"))
        assert f"scene={scene}" in text and "seed=1" in text and "mu=0.5" in text, text
    # FC/II is the reduction of FC/I: W = H^T M^-1 H, q = H^T M^-1 f + w
    g, l = fcref.load(str(out)), fcref.load(str(local))
    import scipy.sparse.linalg as sla
    Minv_H = sla.spsolve(g["M"].tocsc(), g["H"].toarray())
    W = g["H"].T @ Minv_H
    q = g["H"].T @ sla.spsolve(g["M"].tocsc(), g["f"]) + g["w"]
    assert np.allclose(l["W"].toarray(), W, rtol=1e-8, atol=1e-10 * abs(W).max())
    assert np.allclose(l["q"], q, rtol=1e-8, atol=1e-10 * abs(q).max())


@needs_fcref
def test_mu_zero_and_penetration_correction(tmp_path):
    _, local, gen = generate(tmp_path, "box-stack", "--mu", 0, "--penetration-correction", 0.5)
    ref = fcref.load(str(local))
    assert ref["d"] == 3 and np.all(ref["mu"] == 0.0)
    solve_and_recheck(local, tmp_path)
    out, _, _ = generate(tmp_path, "sphere-pile", "--penetration-correction", 0.0)
    assert not np.any(fcref.load(str(out))["w"])  # no correction, no restitution: w = 0
    out, _, _ = generate(tmp_path, "sphere-pile", "--penetration-correction", 1.0, contacts=40)
    w = fcref.load(str(out))["w"]
    assert np.all(w[0::3] <= 0) and not np.any(w[1::3]) and not np.any(w[2::3])


def test_same_seed_same_problem_other_seed_other_problem(tmp_path):
    def f_of(seed, sub):
        d = tmp_path / sub
        d.mkdir()
        out, _, _ = generate(d, "wall", "--seed", seed, contacts=40)
        with h5py.File(out, "r") as f:
            return f["fclib_global/vectors/f"][()]
    a, b, c = f_of(3, "a"), f_of(3, "b"), f_of(4, "c")
    assert np.array_equal(a, b)
    assert a.shape != c.shape or not np.array_equal(a, c)


@needs_fcref
def test_mass_ratio_reaches_the_mass_matrix(tmp_path):
    out, _, _ = generate(tmp_path, "heavy-on-light", "--mass-ratio", 1e4, contacts=24)
    M = fcref.load(str(out))["M"].diagonal()
    assert np.count_nonzero(fcref.load(str(out))["M"] - np.diag(M)) == 0  # rigid bodies: M diagonal
    masses = M[0::6]  # (m, m, m, J_x, J_y, J_z) per body
    assert masses.max() / masses.min() == pytest.approx(1e4)


BAD = [
    (["generate", "no-such-scene", "--out", "x.hdf5"], "unknown scene"),
    (["generate", "wall", "--contacts", "2", "--out", "x.hdf5"], "--contacts"),
    (["generate", "wall", "--contacts", "many", "--out", "x.hdf5"], "not an integer"),
    (["generate", "wall", "--mu", "3", "--out", "x.hdf5"], "--mu"),
    (["generate", "wall", "--mass-ratio", "0.5", "--out", "x.hdf5"], "--mass-ratio"),
    (["generate", "fem-block", "--mass-ratio", "10", "--out", "x.hdf5"], "--mass-ratio"),
    (["generate", "wall", "--penetration-correction", "2", "--out", "x.hdf5"], "--penetration-correction"),
    (["generate", "wall", "--steps", "0", "--out", "x.hdf5"], "--steps"),
    (["generate", "wall"], "--out"),
    (["generate", "wall", "--out", "x.hdf5", "--bogus", "1"], "unknown option --bogus"),
    (["generate", "fem-block", "--contacts", "5000", "--local-out", "x.hdf5"], "dense W"),
    (["generate", "--out", "x.hdf5"], "exactly one SCENE"),
]


@pytest.mark.parametrize("args,message", BAD, ids=[" ".join(a[1:3]) for a, _ in BAD])
def test_bad_options_exit_2(tmp_path, args, message):
    args = [str(tmp_path / a) if a == "x.hdf5" else a for a in args]
    p = run(*args)
    assert p.returncode == 2, (p.stdout, p.stderr)
    assert message in p.stderr
    assert not (tmp_path / "x.hdf5").exists()


def test_check_on_a_pile_above_the_diagnostics_limit(tmp_path):
    # a generated pile of 1100 contacts (m = 3300 > 3000): `check` answers
    # the existence question and d nc / n, and leaves out the rank, whose
    # sparse QR takes minutes at piles of 5000 (docs/results.md, stop 64).
    # The FC/II's sparse W still gets lambda_max from Lanczos; its lambda_min
    # is not claimed (a pile's W has no Cholesky factor) and cond_W is inf
    # (JSON null); FC/I forms no W above the limit.
    out, local, _ = generate(tmp_path, "sphere-pile", contacts=1100)
    for path, rank in ((out, "rank_H"), (local, "rank_W")):
        p = run("check", path, "--json")
        assert p.returncode == 0, p.stderr
        d = json.loads(p.stdout)
        assert d["m"] > 3000 and d[rank] == -1 and d["cond_W"] is None, d
        assert d["lambda_min_W"] is None, d
        if rank == "rank_W":
            assert d["lambda_max_W"] > 0, d
        else:
            assert d["lambda_max_W"] is None, d
        assert d["verdict"] in ("solution-exists", "not-established"), d
        text = run("check", path)
        assert text.returncode == 0, text.stderr
        assert f"{rank}=nan/{d['m']}" in text.stdout, text.stdout
        if rank == "rank_H":
            assert 1.0 <= d["contact_ratio"] < 1.1, d  # two contacts a sphere


def test_check_of_both_forms_of_a_heavy_on_light_stack(tmp_path):
    # mass ratio 1e4: W is sparse and ill-conditioned, where the program with
    # H^T = W (metric ||r||^2) finds no witness and the Cholesky form (H^T a
    # factor of W + eps I, FC/I's metric) does (ipm/existence_check.hpp); the
    # FC/II verdict must agree with its FC/I form's (the certificate itself
    # is checked in tests/test_ipm.cpp on such a stack)
    out, local, _ = generate(tmp_path, "heavy-on-light", "--mass-ratio", "1e4", "--seed", "901", contacts=40)
    verdicts = {}
    for path in (out, local):
        p = run("check", path, "--json")
        assert p.returncode == 0, p.stderr
        d = json.loads(p.stdout)
        assert d["check_program"] == ("global-form" if d["kind"] == "global" else "cholesky-form"), d
        verdicts[d["kind"]] = d["verdict"]
    assert verdicts == {"global": "solution-exists", "local": "solution-exists"}
    text = run("check", local)
    assert "check_program=" in text.stdout, text.stdout


def test_check_honours_max_time(tmp_path):
    # a box stack of 300 contacts: its program needs some 20 interior-point
    # iterations; cut at 1 ms it reports check_status timeout, and says a
    # solution exists only if the witness it had reached is certified
    # (margin > 0, checked against the data); unlimited it stops at its
    # first certified witness (or converges)
    out, local, _ = generate(tmp_path, "box-stack", contacts=300)
    for path in (out, local):
        full = run("check", path, "--json")
        assert full.returncode == 0, full.stderr
        d = json.loads(full.stdout)
        assert d["check_status"] in ("certified", "converged") and d["verdict"] == "solution-exists", d
        assert d["x_star"] > 0 and d["margin"] > 0 and d["check_iterations"] > 0, d
        # --to-optimum: the program runs on to x*, past the certified witness
        opt = json.loads(run("check", path, "--to-optimum", "--json").stdout)
        assert opt["check_status"] not in ("certified", "timeout") and opt["verdict"] == "solution-exists", opt
        assert opt["check_iterations"] >= d["check_iterations"] and opt["x_star"] > 0, (opt, d)
        cut = run("check", path, "--max-time", "0.001", "--json")
        assert cut.returncode == 0, cut.stderr
        c = json.loads(cut.stdout)
        # the clock is read after each iteration's certificate: on a loaded
        # machine the first iterations can outlast 1 ms and certify first
        assert c["check_status"] == "timeout" or (
            c["check_status"] == "certified" and c["check_iterations"] <= d["check_iterations"]), (c, d)
        assert (c["verdict"] == "solution-exists") == (c["margin"] > 0), c
        assert c["m"] == d["m"] and c["lambda_max_W"] == d["lambda_max_W"], c  # the diagnostics still run
    for bad in ("0", "-1", "nan"):
        p = run("check", out, "--max-time", bad)
        assert p.returncode == 2 and "max-time" in p.stderr, (bad, p.stderr)
