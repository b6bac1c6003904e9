"""The CLI and Python accept and reject exactly the same solve requests.

One table of (tol, max_iter, max_time) runs through both front ends; the
registry checks the values once (registry::detail::check_common). The CLI
rejects with exit code 2, Python with ValueError (fcsolve.UsageError).
"""
import math
import os
import subprocess

import pytest

import fcsolve
from conftest import data_file

CLI = os.environ.get("FCSOLVE_CLI")
FILE = "Rover1039.hdf5"  # 4 contacts: every accepted request solves in milliseconds

# (tol, max_iter, max_time, accepted); None: the option is not given.
REQUESTS = [
    (1e-8, None, None, True),
    (1e-300, 1, 1e-3, True),      # valid, even if tol is out of reach
    (0.0, None, None, False),
    (-1e-8, None, None, False),
    (math.nan, None, None, False),
    (math.inf, None, None, False),
    (1e-8, 0, None, False),
    (1e-8, -5, None, False),
    (1e-8, 10**9, None, True),
    (1e-8, 10**9 + 1, None, False),
    (1e-8, 2**40, None, False),
    (1e-8, None, 0.0, False),
    (1e-8, None, -1.0, False),
    (1e-8, None, math.nan, False),
    (1e-8, None, math.inf, True),  # no time limit
]


def cli_accepts(path, tol, max_iter, max_time):
    args = [CLI, "solve", str(path), "--solver", "nsgs", "--tol", repr(tol)]
    if max_iter is not None:
        args += ["--max-iter", str(max_iter)]
    if max_time is not None:
        args += ["--max-time", repr(max_time)]
    proc = subprocess.run(args, capture_output=True, text=True, timeout=60)
    assert proc.returncode in (0, 1, 2), proc.stderr
    return proc.returncode != 2, proc.stderr


def python_accepts(problem, tol, max_iter, max_time):
    try:
        fcsolve.solve(problem, "nsgs", tol=tol, max_iter=max_iter, max_time=max_time)
    except ValueError as e:
        return False, str(e)
    return True, ""


@pytest.mark.parametrize("tol,max_iter,max_time,accepted", REQUESTS)
def test_cli_and_python_agree(tol, max_iter, max_time, accepted):
    if not CLI or not os.path.exists(CLI):
        pytest.skip("FCSOLVE_CLI does not name the built fcsolve program (set by CTest)")
    path = data_file(FILE)
    by_cli, cli_message = cli_accepts(path, tol, max_iter, max_time)
    by_python, py_message = python_accepts(fcsolve.load(path), tol, max_iter, max_time)
    assert by_cli == accepted, cli_message
    assert by_python == accepted, py_message
    if not accepted:  # the same check, so the same words
        assert py_message.strip() in cli_message, (cli_message, py_message)
