"""Shared by the campaign tests: the campaign package (imported without the
compiled extension when that is not built), paths, and small FCLIB files
whose exact solution is r = 0."""
import importlib.util
import os
import sys
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parents[2]
CAMPAIGN_DIR = ROOT / "python" / "fcsolve" / "campaign"
BUNDLED = ROOT / "examples" / "data"
SHARED = Path(os.environ.get("FCSOLVE_SHARED_DATA", ROOT.parent / "shared" / "data" / "fclib"))
FCREF = SHARED.parent.parent / "tools" / "fcref.py"
FAKE_CLI = Path(__file__).resolve().parent / "fake_fcsolve.py"


def _campaign():
    try:
        import fcsolve  # noqa: F401  the full package when it imports (extension built)
    except ImportError:
        pass  # not built: the bootstrap registers a bare package
    spec = importlib.util.spec_from_file_location("_fcsolve_campaign_bootstrap",
                                                  CAMPAIGN_DIR / "bootstrap.py")
    bootstrap = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bootstrap)
    return bootstrap.import_campaign(str(CAMPAIGN_DIR))


campaign = _campaign()


def real_cli():
    """The built fcsolve binary, or None."""
    path = os.environ.get("FCSOLVE_CLI", str(ROOT / "build" / "fcsolve"))
    return path if os.path.isfile(path) and os.access(path, os.X_OK) else None


def _matrix(group, A):
    """Writes A as an FCLIB compressed-column matrix."""
    import scipy.sparse as sp

    A = sp.csc_matrix(A)
    for name, value in (("m", A.shape[0]), ("n", A.shape[1]), ("nz", -1), ("nzmax", A.nnz)):
        group.create_dataset(name, data=np.array([value], dtype=np.int32))
    group.create_dataset("p", data=A.indptr.astype(np.int32))
    group.create_dataset("i", data=A.indices.astype(np.int32))
    group.create_dataset("x", data=A.data.astype(float))


def write_trivial_problem(path, kind="local", nc=2, mu=0.5):
    """W = I (or M = H = I), q (or f) = (1, 0, 0) per contact: every contact
    separates, so r = 0 (with v = f) is the exact solution, error 0."""
    m = 3 * nc
    free = np.tile([1.0, 0.0, 0.0], nc)
    with h5py.File(path, "w") as f:
        g = f.create_group(f"fclib_{kind}")
        g.create_dataset("spacedim", data=np.array([3], dtype=np.int32))
        v = g.create_group("vectors")
        v.create_dataset("mu", data=np.full(nc, mu))
        if kind == "local":
            _matrix(g.create_group("W"), np.eye(m))
            v.create_dataset("q", data=free)
        else:
            _matrix(g.create_group("M"), np.eye(m))
            _matrix(g.create_group("H"), np.eye(m))
            v.create_dataset("f", data=free)
            v.create_dataset("w", data=np.zeros(m))
    return str(path)
