"""`fcsolve bench`: every problem x solver x tolerance, resumable, into one CSV."""
import datetime
import json
import os
import platform
import subprocess
import sys

from . import problems as _problems
from . import solvers as _solvers
from .executors import make_executor
from .progress import Progress
from .results import ResultsFile, run_key
from .tasks import Task, log_name

# Solved runs faster than this (seconds) are timed again in a hot loop
# (tasks._hot_loop): short solves are measured hot, not as the first call of
# a fresh process. Up to 0.1 s the first call still pays for memory touched
# the first time (Spheres-i099, FC/I: `auto` 10.0 ms alone, 5.7 ms as the
# fastest of 3, its reduction 8.0 against 4.3 ms; docs/results.md).
HOT_BELOW = 0.1


def _solution_path(out_dir, task_name):
    return os.path.join(out_dir, "solutions", task_name.replace(".log", ".hdf5"))


def plan(problem_files, solver_specs, tols, timeout, out_dir, grace=2.0, max_iter=None,
         keep_solutions=False, done=frozenset(), repeat=1, hot_below=0.0):
    """(tasks still to run, (problem, solver) pairs not supported, (file, why) unreadable)."""
    out_dir = os.path.abspath(out_dir)  # runs may execute elsewhere (Dask workers)
    files = _problems.find_problem_files(problem_files)
    if not files:
        raise RuntimeError("no problem file given")
    names = _problems.problem_names(files)
    task_list, unsupported, unreadable = [], [], []
    for path, name in zip(files, names):
        try:
            info = _problems.problem_info(path)
        except (OSError, KeyError, ValueError) as e:  # not an FCLIB problem: say so, go on
            unreadable.append((path, f"{type(e).__name__}: {e}"))
            continue
        meta = dict(kind=info["kind"], nc=info["nc"], n=info["n"], m=info["m"],
                    family=_problems.problem_family(name))
        for s in solver_specs:
            if not s.supports(info["kind"]):
                unsupported.append((name, s.name))
                continue
            for tol in tols:
                if run_key(name, s.name, tol) in done:
                    continue
                t = Task(problem=name, file=os.path.abspath(path), solver=s.name, tol=float(tol),
                         timeout=float(timeout), kill_after=float(timeout) + grace, argv=[],
                         solution="", log_dir=os.path.join(out_dir, "logs"), meta=meta,
                         keep_solution=keep_solutions, repeat=max(1, int(repeat)),
                         hot_below=float(hot_below))
                t.solution = os.path.abspath(_solution_path(out_dir, log_name(t)))
                t.argv = s.command(t.file, tol, timeout, t.solution, max_iter)
                task_list.append(t)
    return task_list, unsupported, unreadable


def _fcsolve_version(fcsolve):
    if not fcsolve:
        return None
    try:
        return subprocess.run([fcsolve, "version"], capture_output=True, text=True,
                              timeout=30).stdout.strip()
    except OSError:
        return None


def _record(out_dir, entry):
    """Appends this invocation to campaign.json (what ran, where, with what)."""
    path = os.path.join(out_dir, "campaign.json")
    history = []
    if os.path.exists(path):
        with open(path) as f:
            history = json.load(f).get("invocations", [])
    history.append(entry)
    with open(path, "w") as f:
        json.dump({"invocations": history}, f, indent=1)


def run_campaign(problem_files, solvers="all", tols=(1e-8,), timeout=20.0, out_dir="campaign",
                 jobs=None, dask=None, fcsolve=None, peer_python=_solvers.DEFAULT_PEER_PYTHON,
                 max_iter=None, grace=2.0, redo=(), keep_solutions=False, repeat=1,
                 hot_below=HOT_BELOW, stream=None):
    """Runs a campaign and returns {"ran": n, "skipped": n, "csv": path}."""
    stream = stream or sys.stdout

    def say(text):
        stream.write(text + "\n")
        stream.flush()

    fcsolve = _solvers.find_fcsolve(fcsolve)
    specs = _solvers.resolve(solvers, fcsolve, peer_python, warn=say)
    results = ResultsFile(out_dir)
    if redo:
        results.drop(set(redo))
    done = results.keys()
    task_list, unsupported, unreadable = plan(problem_files, specs, tols, timeout, out_dir, grace,
                                              max_iter, keep_solutions, done, repeat,
                                              hot_below)
    skipped = len(done)
    executor = make_executor(jobs, dask)
    say(f"fcsolve bench: {len(task_list)} runs to do ({skipped} already in {results.path}), "
        f"solvers {', '.join(s.name for s in specs)}, tol {', '.join(f'{t:g}' for t in tols)}, "
        f"limit {timeout:g} s, {executor.describe()}")
    for path, why in unreadable:
        say(f"  skipped {path}: {why}")
    for problem, solver in sorted(set(unsupported)):
        say(f"  not run: {solver} does not solve {problem} (kind not supported)")
    _record(out_dir, dict(
        date=datetime.datetime.now().isoformat(timespec="seconds"), host=platform.node(),
        cpus=os.cpu_count(), machine=platform.machine(), fcsolve=fcsolve,
        fcsolve_version=_fcsolve_version(fcsolve), executor=executor.describe(),
        solvers=[dict(name=s.name, family=s.family, peer=s.peer) for s in specs],
        tols=[float(t) for t in tols], timeout=timeout, max_iter=max_iter, repeat=repeat,
        hot_below=hot_below,
        runs=len(task_list)))
    progress = Progress(len(task_list), stream=stream)
    try:
        for row in executor.run(task_list):
            results.append(row)
            progress.update(row)
    finally:
        executor.close()
        solutions = os.path.join(out_dir, "solutions")
        if os.path.isdir(solutions) and not os.listdir(solutions):
            os.rmdir(solutions)
    say("fcsolve bench: " + progress.summary() + f"; results in {results.path}")
    return dict(ran=progress.done, skipped=skipped, csv=results.path)
