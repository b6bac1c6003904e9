"""Shared fixtures: where the FCLIB files are, the independent checker fcref.

The shared collection ../shared/data/fclib (beside the checkout) is used when
present, the files bundled in examples/data otherwise (a fresh clone). fcref
(../shared/tools/fcref.py) is imported from there; tests that need it skip
without it, and the solver tests fall back on fcsolve's own error.
"""

import importlib.util
import os
from pathlib import Path

import pytest

import fcsolve

ROOT = Path(__file__).resolve().parents[2]
# $FCSOLVE_SHARED_DATA (the data/fclib folder) overrides ../shared: CI points
# it at an empty place to run the tests as a lone clone has them.
if os.environ.get("FCSOLVE_SHARED_DATA"):
    SHARED_DATA = Path(os.environ["FCSOLVE_SHARED_DATA"]).resolve()
    SHARED = SHARED_DATA.parent.parent
else:
    SHARED = (ROOT / ".." / "shared").resolve()
    SHARED_DATA = SHARED / "data" / "fclib"
BUNDLED_DATA = ROOT / "examples" / "data"


def have_shared_data():
    return (SHARED_DATA / "local").is_dir()


def data_file(name):
    """A problem by file name: from the shared collection if there, else bundled."""
    for sub in ("local", "global"):
        path = SHARED_DATA / sub / name
        if path.exists():
            return path
    path = BUNDLED_DATA / name
    if not path.exists():
        pytest.skip(f"{name} is neither in {SHARED_DATA} nor in {BUNDLED_DATA}")
    return path


def all_files(kind):
    """Every FCLIB file of a kind ('local' or 'global')."""
    if have_shared_data():
        return sorted((SHARED_DATA / kind).glob("*.hdf5"))
    files = []
    for path in sorted(BUNDLED_DATA.glob("*.hdf5")):
        if isinstance(fcsolve.load(path), fcsolve.LocalProblem) == (kind == "local"):
            files.append(path)
    return files


def load_fcref():
    path = SHARED / "tools" / "fcref.py"
    if not path.exists():
        return None
    spec = importlib.util.spec_from_file_location("fcref", path)
    module = importlib.util.module_from_spec(spec)
    try:
        spec.loader.exec_module(module)
    except ImportError:  # h5py missing
        return None
    return module


FCREF = load_fcref()


@pytest.fixture
def fcref():
    if FCREF is None:
        pytest.skip(f"the reference checker {SHARED / 'tools' / 'fcref.py'} (or h5py) is absent")
    return FCREF


def reference_error(path, problem, r, v=None):
    """fcref's error of (r, v) when fcref is here, else fcsolve's own."""
    if FCREF is not None and getattr(problem, "G", None) is None:
        return FCREF.error(FCREF.load(str(path)), r, v)
    if isinstance(problem, fcsolve.GlobalProblem):
        return problem.error(r, v)
    return problem.error(r)


SOLVER_NAMES = [s.name for s in fcsolve.solvers()]


def solver_params():
    """One pytest param per registered solver, or a skip saying none is."""
    if not SOLVER_NAMES:
        return [pytest.param(None, marks=pytest.mark.skip(
            reason="no solver is registered in this build of fcsolve"))]
    return SOLVER_NAMES
