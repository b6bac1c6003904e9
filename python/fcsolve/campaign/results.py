"""The campaign's CSV: one row per problem x solver x tolerance.

`error` is the campaign's own recomputation from the solution file the run
returned (fclib_error.py); `own_error` is what the solver reported. A run is
solved iff error <= tol, and then its failure class is "converged".
"""
import csv
import math
import os

# The columns, in order. The first thirteen are the campaign's contract; the
# rest help reading a campaign (family for grouping, where the time went, why
# a run failed).
COLUMNS = [
    "problem", "kind", "nc", "n", "m", "solver", "tol", "status", "seconds",
    "iterations", "own_error", "error", "failure",
    "solved", "family", "time_limit", "wall_seconds", "exit_code", "message", "file",
]

# Failure classes. "inaccurate": the solver claimed convergence but the
# recomputed error exceeds tol (peers with their own error scaling).
FAILURE_CLASSES = [
    "converged", "max-iterations", "stalled", "diverged", "nan", "inaccurate",
    "timeout", "crash",
]

CSV_NAME = "results.csv"


def format_tol(tol):
    """The tolerance as written in the CSV (shortest round-trip text)."""
    return repr(float(tol))


def run_key(problem, solver, tol):
    """What identifies a run: resuming skips rows with a key already present."""
    return (problem, solver, float(tol))


def csv_path(out_dir):
    return os.path.join(out_dir, CSV_NAME)


def _text(value):
    if value is None:
        return ""
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else str(value).lower()
    return str(value)


class ResultsFile:
    """Append-only CSV with the schema above; written row by row, so an
    interrupted campaign keeps every finished run."""

    def __init__(self, out_dir):
        self.path = csv_path(out_dir)
        os.makedirs(out_dir, exist_ok=True)
        if os.path.exists(self.path) and os.path.getsize(self.path) > 0:
            with open(self.path, newline="") as f:
                header = next(csv.reader(f), None)
            if header != COLUMNS:
                raise ValueError(f"{self.path} has columns {header}, expected {COLUMNS}: "
                                 "use another --out folder")
        else:
            with open(self.path, "w", newline="") as f:
                csv.writer(f).writerow(COLUMNS)

    def keys(self):
        return {run_key(r["problem"], r["solver"], r["tol"]) for r in read_rows(self.path)}

    def append(self, row):
        with open(self.path, "a", newline="") as f:
            csv.writer(f).writerow([_text(row.get(c)) for c in COLUMNS])

    def drop(self, failures):
        """Removes the rows whose failure class is in `failures` (to run them again)."""
        rows = [r for r in read_rows(self.path) if r["failure"] not in failures]
        tmp = self.path + ".tmp"
        with open(tmp, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(COLUMNS)
            for r in rows:
                w.writerow([r.get(c, "") for c in COLUMNS])
        os.replace(tmp, self.path)


def read_rows(path):
    """Rows as dicts of strings (the CSV as written)."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def _number(text, kind=float):
    if text in ("", None):
        return None
    try:
        return kind(text)
    except ValueError:
        return kind(float(text)) if kind is int else float("nan")


def load_results(path):
    """Rows with typed values: numbers as float/int (None when empty), solved as bool."""
    if os.path.isdir(path):
        path = csv_path(path)
    rows = []
    for r in read_rows(path):
        t = dict(r)
        for c in ("tol", "seconds", "own_error", "error", "time_limit", "wall_seconds"):
            t[c] = _number(r.get(c))
        for c in ("nc", "n", "m", "iterations", "exit_code"):
            t[c] = _number(r.get(c), int)
        t["solved"] = solved(t["error"], t["tol"])
        rows.append(t)
    return rows


def solved(error, tol):
    """The campaign's one criterion: the recomputed error is within tol."""
    return error is not None and tol is not None and math.isfinite(error) and error <= tol
