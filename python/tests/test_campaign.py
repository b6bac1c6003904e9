"""Campaign runner (`fcsolve bench`): the CSV schema, resumption, timeouts
(the whole process group killed), crashes, false convergence claims, the
peers' adapter, the Dask executor and the CLI forwarding. Misbehaving
solvers come from fake_fcsolve.py; real runs use the built binary."""
import csv
import io
import os
import signal
import subprocess
import sys
import time

import pytest

from campaign_support import (BUNDLED, FAKE_CLI, ROOT, campaign, real_cli,
                              write_trivial_problem)

from fcsolve.campaign import results, runner, solvers

BRIEF_COLUMNS = ["problem", "kind", "nc", "n", "m", "solver", "tol", "status", "seconds",
                 "iterations", "own_error", "error", "failure"]
needs_cli = pytest.mark.skipif(real_cli() is None, reason="build/fcsolve not built")


def assert_gone(pid):
    """The process `pid` ends within 5 s."""
    for _ in range(50):
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return
        time.sleep(0.1)
    pytest.fail(f"process {pid} is still alive")


def bench(problems, out, **kw):
    kw.setdefault("fcsolve", str(FAKE_CLI))
    kw.setdefault("jobs", 2)
    log = io.StringIO()
    summary = runner.run_campaign([str(p) for p in problems], out_dir=str(out), stream=log, **kw)
    return summary, results.load_results(str(out)), log.getvalue()


@pytest.fixture
def trivial(tmp_path):
    return [write_trivial_problem(tmp_path / "Trivial-i1-2.hdf5"),
            write_trivial_problem(tmp_path / "TrivialGlobal3.hdf5", kind="global", nc=3)]


def test_schema_and_false_claims(tmp_path, trivial):
    problems = trivial + [BUNDLED / "Rover1039.hdf5"]
    summary, rows, log = bench(problems, tmp_path / "c", solvers="zero", tols=[1e-4, 1e-8])
    assert summary["ran"] == 6 and len(rows) == 6
    with open(tmp_path / "c" / "results.csv", newline="") as f:
        header = next(csv.reader(f))
    assert header[: len(BRIEF_COLUMNS)] == BRIEF_COLUMNS and header == results.COLUMNS
    by = {(r["problem"], r["tol"]): r for r in rows}
    for tol in (1e-4, 1e-8):
        r = by[("Trivial-i1-2", tol)]
        assert (r["kind"], r["nc"], r["n"], r["m"]) == ("local", 2, None, 6)
        assert r["error"] == 0.0 and r["failure"] == "converged" and r["solved"]
        g = by[("TrivialGlobal3", tol)]
        assert (g["kind"], g["nc"], g["n"], g["m"]) == ("global", 3, 9, 9)
        assert g["failure"] == "converged" and g["error"] == 0.0
        # r = 0 on a real problem: the fake claims convergence, the recomputed
        # error (not the claim) decides
        rover = by[("Rover1039", tol)]
        assert rover["status"] == "converged" and rover["own_error"] == 0.0
        assert rover["error"] > 1e-2 and rover["failure"] == "inaccurate" and not rover["solved"]
        assert rover["family"] == "Rover" and rover["time_limit"] == 20.0
    assert not (tmp_path / "c" / "solutions").exists()  # solution files removed
    assert "6 runs" in log


def test_resume_adds_nothing_and_redo_reruns(tmp_path, trivial):
    out = tmp_path / "c"
    first, rows, _ = bench(trivial, out, solvers="zero", tols=[1e-6])
    assert first["ran"] == 2
    again, rows2, log = bench(trivial, out, solvers="zero", tols=[1e-6])
    assert again == dict(ran=0, skipped=2, csv=first["csv"]) and len(rows2) == 2
    # a new tolerance adds only its own rows
    more, rows3, _ = bench(trivial, out, solvers="zero", tols=[1e-6, 1e-9])
    assert more["ran"] == 2 and len(rows3) == 4
    # --redo: the rows of a failure class are run again, not duplicated
    rover = BUNDLED / "Rover1039.hdf5"
    bench([rover], out, solvers="zero", tols=[1e-6])
    redo, rows4, _ = bench([rover], out, solvers="zero", tols=[1e-6], redo=["inaccurate"])
    assert redo["ran"] == 1 and len(rows4) == 5


def test_repeat_keeps_the_fastest_time(tmp_path, trivial, monkeypatch):
    monkeypatch.setenv("FAKE_COUNT_FILE", str(tmp_path / "calls"))
    _, (row,), _ = bench(trivial[:1], tmp_path / "once", solvers="slowfirst")
    assert row["seconds"] == 1.0
    (tmp_path / "calls").unlink()
    _, (row,), _ = bench(trivial[:1], tmp_path / "thrice", solvers="slowfirst", repeat=3)
    assert row["seconds"] == 0.25 and row["failure"] == "converged"
    assert (tmp_path / "calls").read_text() == "3"


def test_short_runs_are_timed_again_in_a_hot_loop(tmp_path, trivial, monkeypatch):
    monkeypatch.setenv("FAKE_COUNT_FILE", str(tmp_path / "calls"))
    # 1 s is above the threshold: one fresh run
    _, (row,), _ = bench(trivial[:1], tmp_path / "cold", solvers="slowfirst", hot_below=0.5)
    assert row["seconds"] == 1.0 and (tmp_path / "calls").read_text() == "1"
    assert "hot loop" not in row["message"]
    (tmp_path / "calls").unlink()
    # below it: the same command again with --repeat N, its (faster) time counts
    _, (row,), _ = bench(trivial[:1], tmp_path / "hot", solvers="slowfirst", hot_below=2.0)
    assert row["seconds"] == 0.25 and row["failure"] == "converged"
    assert (tmp_path / "calls").read_text() == "2"
    assert "hot loop: fastest of 3 solves in one process" in row["message"]


def test_timeout_kills_the_process_group(tmp_path, trivial, monkeypatch):
    pid_file = tmp_path / "child.pid"
    monkeypatch.setenv("FAKE_PID_FILE", str(pid_file))
    start = time.monotonic()
    _, rows, _ = bench(trivial[:1], tmp_path / "c", solvers="sleepy", timeout=0.5, grace=0.5)
    assert time.monotonic() - start < 15
    (row,) = rows
    assert row["failure"] == "timeout" and row["status"] == "timeout" and row["error"] is None
    assert 0.9 <= row["wall_seconds"] < 10 and "killed after" in row["message"]
    # a solver that stops itself at its time limit: a timeout too, not killed
    _, (tired,), _ = bench([BUNDLED / "Rover1039.hdf5"], tmp_path / "t", solvers="tired")
    assert tired["failure"] == "timeout" and tired["error"] > 1e-8 and not tired["message"]
    assert_gone(int(pid_file.read_text()))  # the sleeping grandchild went with its group
    logs = os.listdir(tmp_path / "c" / "logs")
    assert len(logs) == 1 and "sleepy" in logs[0]


def test_ctrl_c_stops_the_campaign_and_its_runs(tmp_path, trivial):
    pid_file = tmp_path / "child.pid"
    env = dict(os.environ, FAKE_PID_FILE=str(pid_file))
    proc = subprocess.Popen(
        [sys.executable, str(ROOT / "python/fcsolve/campaign/__main__.py"), "bench", trivial[0],
         "--fcsolve", str(FAKE_CLI), "--solvers", "sleepy", "--tol", "1e-2,1e-3,1e-4",
         "--timeout", "60", "--jobs", "1", "--out", str(tmp_path / "c")],
        env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    for _ in range(100):  # wait for the first run to be under way
        if pid_file.exists() and pid_file.read_text():
            break
        time.sleep(0.1)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=20)
    assert proc.returncode == 130 and "interrupted" in err
    assert_gone(int(pid_file.read_text()))
    assert results.load_results(str(tmp_path / "c")) == []  # the killed run is not recorded


def test_crashes_are_recorded(tmp_path, trivial):
    junk = tmp_path / "junk.hdf5"
    junk.write_bytes(b"not an HDF5 file")
    _, rows, log = bench(trivial[:1] + [junk], tmp_path / "c", solvers="suicidal,mute")
    assert f"skipped {junk}" in log  # an unreadable file is reported, the campaign goes on
    by = {r["solver"]: r for r in rows}
    assert by["suicidal"]["failure"] == "crash" and by["suicidal"]["exit_code"] == -11
    assert "signal 11" in by["suicidal"]["message"]
    assert by["mute"]["failure"] == "crash" and by["mute"]["exit_code"] == 0


def test_unknown_solver_and_missing_peer(tmp_path, trivial):
    with pytest.raises(RuntimeError, match="unknown solver 'nope'"):
        bench(trivial, tmp_path / "c", solvers="zero,nope")
    # a peer that cannot run is skipped with a message; nothing else to run: error
    log = io.StringIO()
    specs = solvers.resolve("zero,siconos:nsgs", str(FAKE_CLI), "/nonexistent/python",
                            warn=lambda m: log.write(m))
    assert [s.name for s in specs] == ["zero"] and "peer 'siconos'" in log.getvalue()
    with pytest.raises(RuntimeError, match="no solver to run"):
        solvers.resolve("siconos:nsgs", None, "/nonexistent/python", warn=lambda m: None)


def siconos_available():
    return subprocess.run(["/usr/bin/python3", "-c", "import siconos.numerics"],
                          capture_output=True).returncode == 0


@pytest.mark.skipif(not siconos_available(), reason="python3-siconos not installed")
def test_siconos_peer_through_the_same_machinery(tmp_path, trivial):
    problems = trivial + [BUNDLED / "Rover1039.hdf5"]
    _, rows, log = bench(problems, tmp_path / "c", solvers="siconos:nsn-ac,siconos:ipm",
                         tols=[1e-8])
    by = {(r["problem"], r["solver"]): r for r in rows}
    assert ("Rover1039", "siconos:ipm") not in by  # Siconos has no local IPM
    assert "siconos:ipm does not solve Rover1039" in log
    for p in ("Trivial-i1-2", "TrivialGlobal3", "Rover1039"):
        r = by[(p, "siconos:nsn-ac")]
        assert r["failure"] == "converged" and r["error"] <= 1e-8 and r["iterations"] >= 0
    # the IPM's claim is judged by the recomputed error, whatever it is
    ipm = by[("TrivialGlobal3", "siconos:ipm")]
    assert ipm["failure"] == ("converged" if ipm["error"] <= 1e-8 else "inaccurate")


def test_dask_local_cluster(tmp_path, trivial):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=True,
                                  host="127.0.0.1", dashboard_address=None,
                                  silence_logs=40) as cluster:
        problems = trivial + [BUNDLED / "Rover1039.hdf5"]
        summary, rows, log = bench(problems, tmp_path / "c", solvers="zero,suicidal",
                                   tols=[1e-6], dask=cluster.scheduler_address)
    assert summary["ran"] == 6 and "dask tcp://127.0.0.1" in log
    by = {(r["problem"], r["solver"]): r["failure"] for r in rows}
    assert by[("Trivial-i1-2", "zero")] == by[("TrivialGlobal3", "zero")] == "converged"
    assert by[("Rover1039", "zero")] == "inaccurate"
    assert {by[(p, "suicidal")] for p in ("Trivial-i1-2", "TrivialGlobal3", "Rover1039")} == {"crash"}


@needs_cli
def test_fcsolve_bench_and_report_from_the_binary(tmp_path, trivial):
    """The C++ CLI forwards to the campaign and makes it run that same binary,
    with every registered solver by default."""
    cli = real_cli()
    specs = solvers.fcsolve_solvers(cli)
    registered = [s.name for s in specs]
    out = tmp_path / "c"
    env = {k: v for k, v in os.environ.items() if k not in ("FCSOLVE_CLI", "PYTHONPATH")}
    done = subprocess.run([cli, "bench", str(BUNDLED / "Rover1039.hdf5"), trivial[1],
                           "--out", str(out), "--tol", "1e-6", "--timeout", "10", "--report"],
                          capture_output=True, text=True, timeout=300, env=env, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    rows = results.load_results(str(out))
    assert sorted({r["solver"] for r in rows}) == sorted(registered)
    # one local and one global problem; global-only solvers skip the local one
    assert len(rows) == sum(s.supports("local") + s.supports("global") for s in specs)
    for r in rows:
        assert r["failure"] in results.FAILURE_CLASSES and r["error"] is not None
        assert r["solved"] == (r["error"] <= 1e-6)
    assert (out / "report" / "report.html").is_file()
    bad = subprocess.run([cli, "report", str(tmp_path / "missing")], capture_output=True,
                         text=True, timeout=60)
    assert bad.returncode == 2 and "not a campaign folder" in bad.stderr


def test_module_entry_point_runs_by_path(tmp_path):
    """`python3 .../campaign/__main__.py` (what the binary execs) works with no
    PYTHONPATH and without the compiled extension."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    done = subprocess.run([sys.executable, str(ROOT / "python/fcsolve/campaign/__main__.py"),
                           "bench", "--help"], capture_output=True, text=True, env=env,
                          cwd=tmp_path, timeout=60)
    assert done.returncode == 0 and "--solvers" in done.stdout
