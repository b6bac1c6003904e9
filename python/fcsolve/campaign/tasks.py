"""One run of a campaign: a solver process on one problem at one tolerance.

Every run, fcsolve's or a peer's, is a command with the interface of
`fcsolve solve FILE --solver NAME --tol T --max-time S --json --out SOL`: it
prints one JSON line (status, iterations, error, seconds, ...) and writes the
solution to SOL. The run gets its own process group and a wall-clock limit;
past it the whole group is killed and the run is a "timeout". A process that
dies or answers nothing usable is a "crash". Either way the campaign goes on.
"""
import dataclasses
import json
import math
import os
import re
import signal
import subprocess
import threading
import time

from . import fclib_error
from .results import solved

_live = set()
_live_lock = threading.Lock()
_stopping = threading.Event()  # set by kill_all: no new process starts


@dataclasses.dataclass
class Task:
    problem: str        # name in the CSV
    file: str           # absolute path of the FCLIB file
    solver: str         # name in the CSV (e.g. "nsgs", "siconos:nsgs")
    tol: float
    timeout: float      # seconds given to the solver (--max-time)
    kill_after: float   # wall-clock seconds before the process group is killed
    argv: list          # the command
    solution: str       # where the command writes its solution
    log_dir: str        # stdout/stderr of failed runs go there
    meta: dict          # kind, nc, n, m, family
    keep_solution: bool = False
    env: dict = None    # extra environment variables
    repeat: int = 1     # runs of the command; the fastest counts (noise on short runs)
    hot_below: float = 0.0  # a solved run faster than this is timed again in a hot loop


# A hot loop repeats the solve for about this long (at most HOT_MAX_SOLVES).
HOT_SECONDS = 0.05
HOT_MAX_SOLVES = 1000


def _run(argv, limit, env):
    """(returncode, stdout, stderr, wall seconds, timed out) of argv under a limit."""
    start = time.perf_counter()
    with _live_lock:
        if _stopping.is_set():
            raise OSError("the campaign is stopping")
        proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                stdin=subprocess.DEVNULL, start_new_session=True, env=env,
                                text=True, errors="replace")
        _live.add(proc)
    try:
        out, err = proc.communicate(timeout=limit)
        timed_out = False
    except subprocess.TimeoutExpired:
        _kill_group(proc)
        out, err = proc.communicate()
        timed_out = True
    finally:
        with _live_lock:
            _live.discard(proc)
    return proc.returncode, out, err, time.perf_counter() - start, timed_out


def _kill_group(proc):
    try:
        os.killpg(proc.pid, signal.SIGKILL)  # the solver and anything it started
    except (ProcessLookupError, PermissionError):
        pass


def kill_all():
    """Kills every running solver process group and starts no new one (Ctrl-C)."""
    with _live_lock:
        _stopping.set()
        procs = list(_live)
    for p in procs:
        _kill_group(p)


def allow_runs():
    """Undoes kill_all for the next campaign in this process."""
    _stopping.clear()


def _report(stdout):
    """The last JSON object printed by the command, or None."""
    for line in reversed(stdout.splitlines()):
        line = line.strip()
        if line.startswith("{"):
            try:
                return json.loads(line)
            except ValueError:
                return None
    return None


def classify(*, timed_out, returncode, report, error, tol):
    """The failure class of a run (results.FAILURE_CLASSES)."""
    if timed_out:
        return "timeout"
    if report is None or returncode not in (0, 1) or error is None:
        return "crash"
    if solved(error, tol):
        return "converged"
    status = report.get("status")
    if not math.isfinite(error) or status == "nan":
        return "nan"
    if status == "converged":
        return "inaccurate"
    if status in ("max-iterations", "stalled", "diverged", "timeout"):
        return status
    return "stalled"


def _solver_seconds(report, wall):
    """The solver's own time (setup + solve), else its call time, else the wall time."""
    if report:
        own = (report.get("setup_seconds") or 0) + (report.get("solve_seconds") or 0)
        if own > 0:
            return float(own)
        if report.get("seconds"):
            return float(report["seconds"])
    return wall


def _safe(text):
    return re.sub(r"[^A-Za-z0-9_.+-]+", "_", text)


def log_name(task):
    return f"{_safe(task.problem)}__{_safe(task.solver)}__{task.tol:g}.log"


def _environment(task):
    env = dict(os.environ)
    # one thread per run: --jobs already spreads runs over the cores
    for k in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        env.setdefault(k, "1")
    env.update(task.env or {})
    return env


def _attempt(task):
    """(returncode, stdout, stderr, wall seconds, timed out) of one run of the command."""
    if os.path.exists(task.solution):
        os.remove(task.solution)
    try:
        return _run(task.argv, task.kill_after, _environment(task))
    except OSError as e:  # the command cannot be started at all
        return None, "", f"{type(e).__name__}: {e}", 0.0, False


def _hot_loop(task, rc, report, seconds):
    """(seconds, note): a short run timed again as the fastest of many solves
    in one process (the command's --repeat N), as sub-millisecond solves
    are measured: the first call of a fresh process pays for code and
    data touched the first time, which a simulation's time loop does not.
    With --repeat K the hot loop runs in K processes (one process' layout
    can be slower throughout) and the fastest counts. The fresh time stays
    when the command refuses --repeat or ends differently."""
    n = max(3, min(HOT_MAX_SOLVES, math.ceil(HOT_SECONDS / seconds)))
    hot = dataclasses.replace(task, argv=list(task.argv) + ["--repeat", str(n)])
    best = None
    for _ in range(max(task.repeat, 1)):
        rc2, out2, _, _, timed_out2 = _attempt(hot)
        again = None if timed_out2 else _report(out2)
        if rc2 != rc or again is None or again.get("status") != report.get("status"):
            break
        hot_seconds = _solver_seconds(again, 0.0)
        if hot_seconds > 0:
            best = hot_seconds if best is None else min(best, hot_seconds)
    if best is None:
        return seconds, ""
    runs = f" (the fastest of {task.repeat} such processes)" if task.repeat > 1 else ""
    return min(seconds, best), f"hot loop: fastest of {n} solves in one process{runs}"


def run_task(task):
    """Runs one task and returns its CSV row (a dict, results.COLUMNS)."""
    os.makedirs(os.path.dirname(task.solution), exist_ok=True)
    rc, out, err, wall, timed_out = _attempt(task)
    report = None if timed_out else _report(out)
    error, note = None, ""
    if report is not None and rc in (0, 1):
        try:
            error = fclib_error.solution_error(task.file, task.solution)
        except Exception as e:  # no or unreadable solution: the run failed
            note = f"no usable solution: {type(e).__name__}: {e}"
    seconds = _solver_seconds(report, wall)
    # --repeat: the same run again, keeping the fastest time of those that end alike
    for _ in range(task.repeat - 1 if error is not None else 0):
        rc2, out2, _, wall2, timed_out2 = _attempt(task)
        again = None if timed_out2 else _report(out2)
        if rc2 != rc or again is None or again.get("status") != report.get("status"):
            break
        seconds, wall = min(seconds, _solver_seconds(again, wall2)), min(wall, wall2)
    hot_note = ""
    if error is not None and solved(error, task.tol) and 0 < seconds < task.hot_below:
        seconds, hot_note = _hot_loop(task, rc, report, seconds)
    failure = classify(timed_out=timed_out, returncode=rc, report=report, error=error, tol=task.tol)
    if timed_out:
        note = f"killed after {wall:.3g} s (limit {task.kill_after:g} s)"
    elif failure == "crash" and not note:
        if rc is not None and rc < 0:
            note = f"killed by signal {-rc}"
        else:
            last = (err.strip().splitlines() or ["no output"])[-1]
            note = f"exit code {rc}: {last}"
    if failure == "crash" or timed_out:
        os.makedirs(task.log_dir, exist_ok=True)
        with open(os.path.join(task.log_dir, log_name(task)), "w") as f:
            f.write(f"$ {' '.join(task.argv)}\n# {note}\n--- stdout\n{out}\n--- stderr\n{err}\n")
    if not task.keep_solution and os.path.exists(task.solution):
        os.remove(task.solution)
    report = report or {}
    message = "; ".join(m for m in (hot_note, report.get("message", ""), note) if m)
    return dict(
        task.meta, problem=task.problem, solver=task.solver, tol=float(task.tol),
        status=report.get("status", failure), seconds=seconds,
        iterations=report.get("iterations"), own_error=report.get("error"), error=error,
        failure=failure, solved=failure == "converged", time_limit=task.timeout,
        wall_seconds=wall, exit_code=rc, message=message.replace("\n", " ")[:300], file=task.file)
