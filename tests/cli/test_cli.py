"""End-to-end checks of the `fcsolve` program against the independent
reference shared/tools/fcref.py: `info` agrees on nc, m, n, nnz for every
shared file, `error` agrees to 1e-10 relative on non-trivial (r, v), and
every malformed input ends with exit code 2 and a message naming the file
and the dataset, never a signal."""
import json
import re
import os
import subprocess
import sys
import time
from pathlib import Path

import h5py
import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
SHARED = Path(os.environ.get("FCSOLVE_SHARED_DATA", ROOT.parent / "shared" / "data" / "fclib"))
TOOLS = SHARED.parent.parent / "tools"
BUNDLED = ROOT / "examples" / "data"
CLI = os.environ.get("FCSOLVE_CLI", str(ROOT / "build" / "fcsolve"))

have_shared = (SHARED / "local").is_dir() and (TOOLS / "fcref.py").is_file()
needs_shared = pytest.mark.skipif(not have_shared, reason="../shared (FCLIB collection, fcref.py) absent")

if have_shared:
    sys.path.insert(0, str(TOOLS))
    import fcref  # noqa: E402  the independent reference, used only to check


def shared_files():
    # Without ../shared, one skipped parameter: an empty list would stop
    # pytest at collection (NotSetType) in a lone clone.
    if not have_shared:
        return [pytest.param(None, marks=pytest.mark.skip(reason="../shared absent"))]
    return sorted(str(p) for p in SHARED.glob("*/*.hdf5"))


def run(*args):
    p = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, timeout=120)
    assert p.returncode >= 0, f"fcsolve died from signal {-p.returncode}: {p.stderr}"
    return p


@needs_shared
@pytest.mark.parametrize("path", shared_files(), ids=lambda p: Path(p).name if p else "none")
def test_info_agrees_with_fcref(path):
    ref = fcref.load(path)
    out = run("info", path, "--json")
    assert out.returncode == 0, out.stderr
    info = json.loads(out.stdout)
    assert info["kind"] == ref["kind"]
    assert info["nc"] == ref["mu"].size
    assert info["d"] == ref["d"]
    if ref["kind"] == "local":
        assert info["m"] == ref["W"].shape[0]
        assert info["nnz_W"] == ref["W"].nnz
    else:
        assert info["n"] == ref["M"].shape[0]
        assert info["m"] == ref["H"].shape[1]
        assert info["nnz_M"] == ref["M"].nnz
        assert info["nnz_H"] == ref["H"].nnz
    # the key=value line carries the same numbers
    line = run("info", path).stdout
    assert f"nc={info['nc']}" in line and f"m={info['m']}" in line


def write_solution(path, r, v=None):
    with h5py.File(path, "w") as f:
        g = f.create_group("solution")
        g["r"] = r
        if v is not None:
            g["v"] = v


@needs_shared
@pytest.mark.parametrize("path", shared_files(), ids=lambda p: Path(p).name if p else "none")
def test_error_agrees_with_fcref(path, tmp_path):
    ref = fcref.load(path)
    rng = np.random.default_rng(abs(hash(Path(path).name)) % 2**32)
    m = ref["mu"].size * ref["d"]
    cases = []
    for k in range(3):
        r = rng.normal(size=m)
        r[0::3] = np.abs(r[0::3]) * (1 + k)  # mostly inside the cone
        v = None
        if ref["kind"] == "global":
            v = rng.normal(size=ref["M"].shape[0]) if k == 2 else None
        cases.append((r, v))
    for i, (r, v) in enumerate(cases):
        sol = tmp_path / f"sol{i}.hdf5"
        write_solution(sol, r, v)
        out = run("error", path, sol, "--json")
        assert out.returncode == 0, out.stderr
        mine = json.loads(out.stdout)["error"]
        theirs = fcref.error(ref, r, v)
        assert mine == pytest.approx(theirs, rel=1e-10, abs=1e-300), (i, mine, theirs)


# --------------------------------------------------------------------- bad input

def make_bad(tmp_path, name, edit, source="Rover1039.hdf5"):
    path = tmp_path / f"{name}.hdf5"
    path.write_bytes((BUNDLED / source).read_bytes())
    with h5py.File(path, "r+") as f:
        edit(f)
    return path


def replace(f, name, value):
    del f[name]
    f[name] = value


BAD_CASES = {
    "missing_q": (lambda f: f.__delitem__("fclib_local/vectors/q"), "fclib_local/vectors/q"),
    "missing_W_x": (lambda f: f.__delitem__("fclib_local/W/x"), "fclib_local/W/x"),
    "short_q": (lambda f: replace(f, "fclib_local/vectors/q", np.ones(5)), "fclib_local/vectors/q"),
    "nan_q": (lambda f: replace(f, "fclib_local/vectors/q", np.r_[np.nan, np.ones(11)]), "fclib_local/vectors/q"),
    "inf_W": (lambda f: replace(f, "fclib_local/W/x", np.r_[np.inf, np.ones(143)]), "fclib_local/W/x"),
    "negative_mu": (lambda f: replace(f, "fclib_local/vectors/mu", np.array([0.7, -0.1, 0.7, 0.7])),
                    "fclib_local/vectors/mu"),
    "index_out_of_range": (lambda f: replace(f, "fclib_local/W/i", np.r_[np.int32(40), np.zeros(143, np.int32)]),
                           "fclib_local/W/i"),
    "bad_storage": (lambda f: replace(f, "fclib_local/W/nz", np.array([-7], np.int32)), "fclib_local/W/nz"),
    "bad_spacedim": (lambda f: replace(f, "fclib_local/spacedim", np.array([9], np.int32)), "fclib_local/spacedim"),
    "missing_group": (lambda f: f.move("fclib_local", "something_else"), ""),
}


@pytest.mark.parametrize("case", sorted(BAD_CASES))
@pytest.mark.parametrize("command", ["info", "solve"])
def test_malformed_file_exits_2_naming_file_and_dataset(tmp_path, case, command):
    edit, dataset = BAD_CASES[case]
    path = make_bad(tmp_path, case, edit)
    args = ["info", path] if command == "info" else ["solve", path, "--solver", first_solver()]
    out = run(*args)
    assert out.returncode == 2, (out.stdout, out.stderr)
    assert str(path) in out.stderr
    assert dataset in out.stderr


def first_solver():
    listing = json.loads(run("solvers", "--json").stdout)
    return listing[0]["name"] if listing else "nsgs"


@pytest.mark.parametrize("content", [b"", b"not an hdf5 file\n", "truncated"])
def test_unreadable_files_exit_2(tmp_path, content):
    path = tmp_path / "broken.hdf5"
    if content == "truncated":
        data = (BUNDLED / "Capsules-i101-404.hdf5").read_bytes()
        path.write_bytes(data[: len(data) // 2])
    else:
        path.write_bytes(content)
    out = run("info", path)
    assert out.returncode == 2
    assert str(path) in out.stderr


def test_missing_file_exits_2(tmp_path):
    out = run("info", tmp_path / "nope.hdf5")
    assert out.returncode == 2 and "nope.hdf5" in out.stderr


@pytest.mark.parametrize("args", [
    [],
    ["frobnicate"],
    ["info"],
    ["info", "a.hdf5", "b.hdf5"],
    ["info", str(BUNDLED / "Rover1039.hdf5"), "--bogus"],
    ["solve", str(BUNDLED / "Rover1039.hdf5"), "--solver", "no-such-solver"],
    ["solve", str(BUNDLED / "Rover1039.hdf5"), "--solver", "vi-fp", "--tol", "abc"],
    ["solve", str(BUNDLED / "Rover1039.hdf5"), "--solver", "vi-fp", "--tol", "-1"],
    ["solve", str(BUNDLED / "Rover1039.hdf5"), "--solver", "vi-fp", "--max-iter", "0"],
    ["solve", str(BUNDLED / "Rover1039.hdf5"), "--solver", "vi-fp", "--repeat", "0"],
])
def test_bad_usage_exits_2(args):
    out = run(*args)
    assert out.returncode == 2, (args, out.stdout, out.stderr)
    assert out.stderr.strip()


def test_error_command_checks_solution_size(tmp_path):
    sol = tmp_path / "short.hdf5"
    write_solution(sol, np.zeros(5))
    out = run("error", BUNDLED / "Rover1039.hdf5", sol)
    assert out.returncode == 2 and "solution/r" in out.stderr


def test_info_on_bundled_files():
    for path in sorted(BUNDLED.glob("*.hdf5")):
        out = run("info", path, "--json")
        assert out.returncode == 0, out.stderr
        info = json.loads(out.stdout)
        assert info["m"] == 3 * info["nc"]


def test_solve_writes_a_solution_fcref_accepts(tmp_path):
    out_file = tmp_path / "sol.hdf5"
    problem = BUNDLED / "Rover1039.hdf5"
    out = run("solve", problem, "--solver", "vi-eg", "--tol", "1e-9", "--out", out_file, "--json")
    assert out.returncode == 0, out.stderr
    res = json.loads(out.stdout)
    assert res["status"] == "converged" and res["error"] <= 1e-9
    # the output is a complete FCLIB file: the problem plus /solution
    again = run("error", out_file, out_file, "--json")
    assert json.loads(again.stdout)["error"] == pytest.approx(res["error"], rel=1e-12)
    if have_shared:
        with h5py.File(out_file) as f:
            r = np.asarray(f["solution/r"])
        assert fcref.error(fcref.load(str(problem)), r) == pytest.approx(res["error"], rel=1e-10)


def test_repeat_solves_again_in_process_with_the_same_result(tmp_path):
    # --repeat N: a hot loop for sub-millisecond problems; deterministic
    # solvers give the same iterate, the fastest time is reported
    problem = BUNDLED / "Rover1039.hdf5"
    once, hot = tmp_path / "once.hdf5", tmp_path / "hot.hdf5"
    a = run("solve", problem, "--solver", "nsgs", "--out", once, "--json")
    b = run("solve", problem, "--solver", "nsgs", "--out", hot, "--json", "--repeat", "20")
    assert a.returncode == 0 and b.returncode == 0, (a.stderr, b.stderr)
    ra, rb = json.loads(a.stdout), json.loads(b.stdout)
    assert ra["iterations"] == rb["iterations"] and ra["error"] == rb["error"]
    with h5py.File(once) as f, h5py.File(hot) as g:
        assert np.array_equal(np.asarray(f["solution/r"]), np.asarray(g["solution/r"]))


def test_solve_exit_1_when_tolerance_not_reached():
    out = run("solve", BUNDLED / "Capsules-i101-404.hdf5", "--solver", "vi-fp", "--max-iter", "3")
    assert out.returncode == 1
    assert "status=max-iterations" in out.stdout


def test_solver_settings_are_typed():
    problem = BUNDLED / "Rover1039.hdf5"
    assert run("solve", problem, "--solver", "vi-eg", "--ratio-max", "0.8").returncode == 0
    bad = run("solve", problem, "--solver", "vi-eg", "--ratio-max", "7")
    assert bad.returncode == 2 and "ratio_max" in bad.stderr
    unknown = run("solve", problem, "--solver", "vi-eg", "--omega", "1")
    assert unknown.returncode == 2 and "omega" in unknown.stderr
    # an enumerated setting: its names, and only on the entry that has it
    assert run("solve", problem, "--solver", "vi-eg", "--second-step", "korpelevich").returncode == 0
    bad_name = run("solve", problem, "--solver", "vi-eg", "--second-step", "backwards")
    assert bad_name.returncode == 2 and "second_step" in bad_name.stderr
    not_here = run("solve", problem, "--solver", "vi-fp", "--second-step", "predictor")
    assert not_here.returncode == 2 and "second-step" in not_here.stderr


def test_nsgs_freeze_tol_reaches_the_solver_and_success_stays_a_full_error(tmp_path):
    problem = BUNDLED / "Capsules-i101-404.hdf5"
    sweeps = {}
    for freeze_tol in ("1e-14", "1e-3"):  # the default, and one that freezes contacts that still move
        out_file = tmp_path / f"s{freeze_tol}.hdf5"
        out = run("solve", problem, "--solver", "nsgs", "--tol", "1e-8", "--freeze-tol", freeze_tol,
                  "--out", out_file)
        assert out.returncode == 0, out.stderr
        sweeps[freeze_tol] = int(re.search(r"iterations=(\d+)", out.stdout).group(1))
        if have_shared:
            with h5py.File(out_file) as f:
                r = np.asarray(f["solution/r"])
            assert fcref.error(fcref.load(str(problem)), r) <= 1e-8
    assert sweeps["1e-3"] > sweeps["1e-14"]  # frozen contacts cost sweeps: the setting was used
    bad = run("solve", problem, "--solver", "nsgs", "--freeze-tol", "2")
    assert bad.returncode == 2 and "freeze_tol" in bad.stderr


def test_nsgs_load_ordering_sorts_once_and_meets_tol(tmp_path):
    # a generated pile: the load order is for scenes whose weight flows through the contacts
    pile, out_file = tmp_path / "pile.hdf5", tmp_path / "r.hdf5"
    gen = run("generate", "sphere-pile", "--contacts", "1000", "--seed", "5", "--local-out", pile)
    assert gen.returncode == 0, gen.stderr
    out = run("solve", pile, "--solver", "nsgs", "--ordering", "load", "--tol", "1e-6",
              "--max-iter", "200000", "--out", out_file)
    assert out.returncode == 0, out.stderr
    assert "status=converged" in out.stdout and "sorted by load" in out.stdout
    if have_shared:
        with h5py.File(out_file) as f:
            r = np.asarray(f["solution/r"])
        assert fcref.error(fcref.load(str(pile)), r) <= 1e-6


def test_global_solve_recovers_v(tmp_path):
    out_file = tmp_path / "gsol.hdf5"
    problem = BUNDLED / "Box_Stacks-i0035-31-0.hdf5"
    out = run("solve", problem, "--solver", "vi-eg", "--out", out_file, "--json")
    assert out.returncode == 0, out.stderr
    with h5py.File(out_file) as f:
        assert f["solution/v"].shape == (450,)
        r, v = np.asarray(f["solution/r"]), np.asarray(f["solution/v"])
    if have_shared:
        assert fcref.error(fcref.load(str(problem)), r, v) <= 1e-8


def test_out_onto_the_input_is_refused_and_the_file_kept(tmp_path):
    problem = tmp_path / "problem.hdf5"
    problem.write_bytes((BUNDLED / "Rover1039.hdf5").read_bytes())
    with h5py.File(problem, "r+") as f:  # a file with guesses, as FCLIB files have
        g = f.create_group("guesses")
        g["number_of_guesses"] = np.array([1], np.int32)
        g.create_group("1")["r"] = np.zeros(12)
    before = problem.read_bytes()
    link = tmp_path / "link.hdf5"
    link.symlink_to(problem)
    for target in (problem, link):
        out = run("solve", problem, "--solver", "nsgs", "--out", target)
        assert out.returncode == 2, (out.stdout, out.stderr)
        assert "input file" in out.stderr
        assert problem.read_bytes() == before


def test_json_output_keeps_a_utf8_title(tmp_path):
    problem = tmp_path / "titled.hdf5"
    problem.write_bytes((BUNDLED / "Rover1039.hdf5").read_bytes())
    title = "μ = 0.7, Ø 2 cm ✓ 𝛍"  # 2-, 3- and 4-byte UTF-8 sequences
    with h5py.File(problem, "r+") as f:
        del f["fclib_local/info/title"]
        f["fclib_local/info/title"] = np.bytes_(title.encode())
    out = run("info", problem, "--json")
    assert out.returncode == 0, out.stderr
    assert out.stdout.isascii()
    assert json.loads(out.stdout)["title"] == title


def _siconos_importable():
    return subprocess.run(["/usr/bin/python3", "-c", "import siconos.numerics"],
                          capture_output=True).returncode == 0


@pytest.mark.parametrize("with_siconos", [False, True])
def test_demo_table_rows_and_peer_column(with_siconos):
    # The main job's table (scripts/demo.sh): one row per file, auto
    # converged on each, and Siconos' column only when it can run.
    if with_siconos and not _siconos_importable():
        pytest.skip("Siconos not importable by /usr/bin/python3 (scripts/deps.sh --peers)")
    files = [BUNDLED / "Rover1039.hdf5", BUNDLED / "GFC3D_Example1.hdf5"]
    args = [sys.executable, str(ROOT / "scripts" / "demo_table.py"), "--cli", CLI,
            "--single-max-time", "2", *map(str, files)]
    if not with_siconos:
        args.append("--no-siconos")
    p = subprocess.run(args, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stdout + p.stderr
    lines = p.stdout.splitlines()
    assert ("siconos best" in lines[0]) == with_siconos
    rows = [line for line in lines if line.split()[:1] in (["Rover1039"], ["GFC3D_Example1"])]
    assert len(rows) == 2 and all("converged" in r for r in rows), p.stdout


def _address_space_limit_of_a_running_solve(preexec=None):
    # the soft "Max address space" of a solve that runs for 3 s (nsgs to an
    # unreachable tol), read from /proc half a second in: the CLI sets its
    # limit before it parses its arguments
    p = subprocess.Popen([CLI, "solve", str(BUNDLED / "Capsules-i101-404.hdf5"), "--solver", "nsgs",
                          "--tol", "1e-300", "--max-iter", "1000000000", "--max-time", "3"],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, preexec_fn=preexec)
    try:
        time.sleep(0.5)
        assert p.poll() is None, "the solve ended before its limit could be read"
        text = Path(f"/proc/{p.pid}/limits").read_text()
        return next(l for l in text.splitlines() if l.startswith("Max address space")).split()[3]
    finally:
        p.kill()
        p.wait()


@pytest.mark.skipif(os.environ.get("FCSOLVE_SANITIZED") == "1" or not Path("/proc/self/limits").exists(),
                    reason="AddressSanitizer builds set no limit; needs Linux /proc")
def test_the_cli_caps_its_address_space_at_the_physical_memory():
    # Linux overcommits: without a limit, a problem too large for the
    # machine ends in the OOM killer instead of "out of memory" (exit 3)
    physical = os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    import resource
    if resource.getrlimit(resource.RLIMIT_AS)[0] != resource.RLIM_INFINITY:
        pytest.skip("this test process already runs under an address-space limit")
    assert _address_space_limit_of_a_running_solve() == str(physical)
    # a limit the caller set is kept
    mine = 6 << 30
    kept = _address_space_limit_of_a_running_solve(
        lambda: resource.setrlimit(resource.RLIMIT_AS, (mine, resource.RLIM_INFINITY)))
    assert kept == str(mine)
