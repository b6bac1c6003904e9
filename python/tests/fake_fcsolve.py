#!/usr/bin/python3
"""A stand-in for the fcsolve binary, to test how a campaign copes with
solvers that misbehave. `solvers --json` lists them; `solve FILE --solver S
--out SOL --json` behaves as S says:
  zero      writes r = 0 (v = f for global problems, exact when M = I) and
            claims convergence: right on trivial problems, a false claim elsewhere
  sleepy    starts a child process (its pid goes to $FAKE_PID_FILE), then sleeps
  suicidal  kills itself with SIGSEGV
  mute      exits 0 and prints nothing
  tired     as zero, but reports its own time limit (status "timeout")
  slowfirst as zero, but reports 1 s on its first call and 0.25 s afterwards
            (calls counted in $FAKE_COUNT_FILE)
"""
import json
import os
import signal
import subprocess
import sys
import time

SOLVERS = ["zero", "sleepy", "suicidal", "mute", "slowfirst", "tired"]


def option(args, name, default=None):
    return args[args.index(name) + 1] if name in args else default


def main(args):
    if args[:1] == ["solvers"]:
        print(json.dumps([dict(name=s, family="fake", local=True, global_native=False, settings=[])
                          for s in SOLVERS]))
        return 0
    if args[:1] == ["version"]:
        print("fcsolve fake")
        return 0
    solver, out = option(args, "--solver"), option(args, "--out")
    if solver == "sleepy":
        child = subprocess.Popen(["sleep", "60"])
        if os.environ.get("FAKE_PID_FILE"):
            with open(os.environ["FAKE_PID_FILE"], "w") as f:
                f.write(str(child.pid))
        time.sleep(60)
        return 0
    if solver == "suicidal":
        os.kill(os.getpid(), signal.SIGSEGV)
    if solver == "mute":
        return 0
    import h5py
    import numpy as np

    with h5py.File(args[1], "r") as f:
        kind = "local" if "fclib_local" in f else "global"
        g = f[f"fclib_{kind}"]
        m = 3 * g["vectors/mu"].shape[0]
        v = np.asarray(g["vectors/f"]) if kind == "global" else None
    with h5py.File(out, "w") as f:
        s = f.create_group("solution")
        s.create_dataset("r", data=np.zeros(m))
        if v is not None:
            s.create_dataset("v", data=v)
    seconds = 0.001
    if solver == "slowfirst":
        count_file = os.environ["FAKE_COUNT_FILE"]
        calls = int(open(count_file).read()) if os.path.exists(count_file) else 0
        with open(count_file, "w") as f:
            f.write(str(calls + 1))
        seconds = 1.0 if calls == 0 else 0.25
    status = "timeout" if solver == "tired" else "converged"
    print(json.dumps(dict(solver=solver, status=status, iterations=0, error=0.0,
                          seconds=seconds, setup_seconds=0.0, solve_seconds=seconds, message="")))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
