"""Problems (FC/II LocalProblem, FC/I GlobalProblem) and FCLIB files."""

import errno
import operator
import os
from collections.abc import Mapping

import numpy as np
import scipy.sparse as sp

from . import _fcsolve
from ._fcsolve import InvalidProblemError, Result


def _invalid(field, message):
    """An InvalidProblemError like the ones C++ raises: 'field: message', .field."""
    exc = InvalidProblemError(f"{field}: {message}")
    exc.field = field
    return exc


def _csc_arguments(A, field):
    """(data, indices, indptr, shape) of A as canonical CSC (float64, int32,
    sorted indices, no duplicates). A: any scipy.sparse matrix/array or a 2-D
    array-like of real numbers."""
    if not sp.issparse(A):
        try:
            A = np.asarray(A)
        except (ValueError, TypeError) as e:
            raise _invalid(field, f"not a matrix ({e})") from None
        if A.ndim != 2:
            raise _invalid(field, f"expected a 2-D matrix (scipy.sparse or numpy), "
                                  f"got {A.ndim} dimension(s)")
    if A.dtype.kind not in "iuf":
        raise _invalid(field, f"expected real numbers, got dtype {A.dtype}")
    C = sp.csc_matrix(A, dtype=np.float64, copy=True)
    C.sum_duplicates()  # sorts the indices too
    if max(C.nnz, *C.shape) >= 2**31:
        raise _invalid(field, "too large for 32-bit indices")
    return (C.data, C.indices.astype(np.int32, copy=False),
            C.indptr.astype(np.int32, copy=False), C.shape)


def _contact_dim(d):
    if isinstance(d, (bool, np.bool_)):  # True is an int to operator.index
        raise _invalid("d", f"contact dimension must be the integer 1, 2 or 3, got {d!r}")
    try:
        return operator.index(d)
    except TypeError:
        raise _invalid("d", f"contact dimension must be the integer 1, 2 or 3, got {d!r}") from None


def _friction(mu, size, d):
    """mu as given, or a scalar broadcast to one value per contact."""
    if mu is not None and np.ndim(mu) == 0 and size is not None and d > 0:
        return np.full(size // d, mu)
    return mu


def _finite(x, field):
    """x unchanged, after checking it holds only finite real numbers: the
    error of a NaN reaction is not a number to return silently."""
    a = np.asarray(x)
    if a.dtype.kind in "iuf" and not np.all(np.isfinite(a)):
        k = int(np.flatnonzero(~np.isfinite(a.ravel()))[0])
        raise _invalid(field, f"non-finite entry ({a.ravel()[k]}) at index {k}")
    return x


def _csc_view(arrays):
    """scipy.sparse.csc_matrix over C++-owned read-only arrays (no copy)."""
    data, indices, indptr, shape = arrays
    return sp.csc_matrix((data, indices, indptr), shape=shape, copy=False)


class _Problem:
    """What LocalProblem and GlobalProblem share."""

    @classmethod
    def _wrap(cls, data):
        obj = cls.__new__(cls)
        obj._data = data
        return obj

    def _matrix(self, name):
        """The C++ matrix `name` as a csc_matrix view, built once (read-only
        attribute: the problem's data cannot be replaced)."""
        cache = self.__dict__.setdefault("_matrices", {})
        if name not in cache:
            arrays = getattr(self._data, name)
            cache[name] = None if arrays is None else _csc_view(arrays)
        return cache[name]

    d = property(lambda self: self._data.d, doc="Contact dimension: 3 (3D Coulomb), 2 or 1 (frictionless).")
    size = property(lambda self: self._data.size, doc="m = d * num_contacts, the number of contact unknowns.")
    num_contacts = property(lambda self: self._data.num_contacts, doc="Number of contacts nc.")
    mu = property(lambda self: self._data.mu, doc="(nc,) friction coefficients (read-only view).")
    title = property(lambda self: self._data.title, doc="FCLIB info/title.")
    description = property(lambda self: self._data.description, doc="FCLIB info/description.")
    math_info = property(lambda self: self._data.math_info, doc="FCLIB info/math_info.")

    def info(self):
        """A summary dict: kind, d, nc, m (n, p for global), stored entries and
        nonzero values of each matrix, mu range, the relative asymmetry
        ||A - A^T||_F / ||A||_F of W (local) or M (global), and the title. The
        same fields as `fcsolve info FILE --json`."""
        return self._data.summary()

    def diagnostics(self):
        """Structural diagnostics that bear on solver robustness, as a dict:
        rank of H (global: rank_H, with contact_ratio = d nc / n; c > 1 forces
        a rank-deficient H) or of W (local: rank_W; -1 when m > 3000: the
        sparse QR's cost grows to minutes on piles of 5000), m, the extreme
        eigenvalues and condition number of the symmetric part of W
        (lambda_min_W, lambda_max_W, cond_W: a sparse W's by Lanczos at any
        size, lambda_min_W 0 where the rank is below m and NaN where W has no
        Cholesky factor, cond_W inf then; a dense W's, and a global
        problem's, NaN when m > 3000) and the relative asymmetry of W. A
        global problem is reduced to get W.
        NotImplementedError if this build lacks the interior-point family."""
        return _interior_point_tool("diagnostics")(self._data)

    def solve(self, solver="auto", **options):
        """Shorthand for fcsolve.solve(self, solver, **options)."""
        from ._solve import solve

        return solve(self, solver, **options)

    def save(self, path, solution=None, guesses=None):
        """Shorthand for fcsolve.save(path, self, solution, guesses)."""
        save(path, self, solution, guesses)


class LocalProblem(_Problem):
    """The reduced frictional contact problem FC/II(W, q, mu): find r, u with

        u = W r + q,   K*  ∋  u + g(u)  ⟂  r  ∈  K     contact by contact,

    K = {||r_T|| <= mu r_N} (normal first in each d-block), g(u) = (mu ||u_T||, 0, 0).

    LocalProblem(W, q, mu, d=3, *, title="", description="", math_info="")

    W: (m, m) scipy.sparse matrix (any format) or 2-D array of real numbers;
       it need not be symmetric (real FCLIB data is not: see info()).
    q: (m,) free velocity.  mu: (nc,) friction coefficients, or one number for
    all contacts (nc = m / d).  d: 3, 2 or 1 (frictionless; mu is ignored).

    The data is checked (shapes, finite values, mu >= 0, dtype) and copied
    once into C++ storage; invalid data raises fcsolve.InvalidProblemError, a
    ValueError whose `field` names the argument. W, q and mu then read that
    storage without copying (read-only numpy arrays, W a scipy csc_matrix).
    fcsolve.load(path) gives the same object from an FCLIB file.
    """

    _solve_impl = staticmethod(_fcsolve.solve_local)

    def __init__(self, W, q, mu, d=3, *, title="", description="", math_info=""):
        d = _contact_dim(d)
        W = _csc_arguments(W, "W")
        # W sets the size (m = rows of W): a q of the wrong length is blamed, not mu
        self._data = _fcsolve.LocalProblemData(
            d, W, q, _friction(mu, W[3][0], d), title, description, math_info)

    W = property(lambda self: self._matrix("W"),
                 doc="(m, m) Delassus operator: a scipy.sparse.csc_matrix over the problem's "
                     "data (no copy; its arrays are read-only).")

    q = property(lambda self: self._data.q, doc="(m,) free velocity (read-only view).")

    def error(self, r):
        """The FCLIB relative error of reactions r: ||r - P_K(r - u~)|| / ||q||
        with u = W r + q (the measure of shared/tools/fcref.py)."""
        return self._data.error(_finite(r, "r"))

    def error_report(self, r):
        """The error of r in several scalings, as a dict: error (FCLIB),
        siconos_error (||F|| / max(||q||, ||r||, ||u||)), absolute (||F||),
        max_contact (max over contacts / ||q||), worst_contact."""
        return self._data.error_report(_finite(r, "r"))

    def __repr__(self):
        return (f"<fcsolve.LocalProblem d={self.d} nc={self.num_contacts} m={self.size} "
                f"nnz(W)={self._data.W[0].size} title={self.title!r}>")


class GlobalProblem(_Problem):
    """The global frictional contact problem FC/I(M, H, f, w, mu), optionally
    with bilateral constraints (G, b) (FCLIB's GM3DFC):

        M v = H r + G lambda + f,   G^T v + b = 0,   u = H^T v + w,
        K*  ∋  u + g(u)  ⟂  r  ∈  K     contact by contact.

    GlobalProblem(M, H, f, w, mu, G=None, b=None, d=3, *, title="", ...)

    M: (n, n), H: (n, m), G: (n, p) scipy.sparse matrices or 2-D arrays;
    f: (n,), w: (m,), b: (p,) vectors; mu: (nc,) or one number; d: 3, 2 or 1.
    M need not be exactly symmetric (the LMGC files are not). Checked and
    copied once like LocalProblem; attributes are read-only views.
    reduce() gives the equivalent LocalProblem (W = H^T M^-1 H, q = H^T M^-1 f + w).
    """

    _solve_impl = staticmethod(_fcsolve.solve_global)

    def __init__(self, M, H, f, w, mu, G=None, b=None, d=3, *, title="", description="",
                 math_info=""):
        d = _contact_dim(d)
        H = _csc_arguments(H, "H")
        # M and H set the sizes (n, m = columns of H): a short f or w is blamed
        self._data = _fcsolve.GlobalProblemData(
            d, _csc_arguments(M, "M"), H, f, w,
            _friction(mu, H[3][1], d), None if G is None else _csc_arguments(G, "G"), b,
            title, description, math_info)

    M = property(lambda self: self._matrix("M"),
                 doc="(n, n) mass matrix: a scipy.sparse.csc_matrix over the problem's data.")
    H = property(lambda self: self._matrix("H"),
                 doc="(n, m) contact operator: a scipy.sparse.csc_matrix over the problem's data.")
    G = property(lambda self: self._matrix("G"),
                 doc="(n, p) bilateral constraint matrix (csc_matrix), or None.")

    f = property(lambda self: self._data.f, doc="(n,) external forces (read-only view).")
    w = property(lambda self: self._data.w, doc="(m,) contact velocity offset (read-only view).")
    b = property(lambda self: self._data.b, doc="(p,) bilateral right-hand side, or None.")
    num_dofs = property(lambda self: self._data.num_dofs, doc="n, the number of degrees of freedom.")

    def reduce(self):
        """The equivalent LocalProblem: W = H^T M^-1 H, q = H^T M^-1 f + w
        (with G, M is replaced by the saddle-point matrix [M -G; G^T 0]).
        M is factorised by Cholesky when symmetric, by LU otherwise; a
        singular M raises InvalidProblemError('M')."""
        return LocalProblem._wrap(self._data.reduce())

    def error(self, r, v=None, multipliers=None):
        """The FCLIB error of (r, v): the larger of the complementarity error
        ||F_nat(r; u = H^T v + w)|| / ||H^T M^-1 f + w|| and the relative
        equilibrium residual of M v = H r (+ G lambda) + f. v defaults to
        M^-1 (H r + f) (and lambda, with G, to its value given r). The
        factorisation of M is computed on the first call and kept."""
        return self._data.error(_finite(r, "r"), None if v is None else _finite(v, "v"),
                                None if multipliers is None else _finite(multipliers, "multipliers"))

    def error_report(self, r, v=None, multipliers=None):
        """The error of (r, v) as a dict: error, complementarity, equilibrium,
        max_contact, worst_contact."""
        return self._data.error_report(
            _finite(r, "r"), None if v is None else _finite(v, "v"),
            None if multipliers is None else _finite(multipliers, "multipliers"))

    def __repr__(self):
        bilateral = f" p={self._data.b.size}" if self._data.b is not None else ""
        return (f"<fcsolve.GlobalProblem d={self.d} nc={self.num_contacts} n={self.num_dofs} "
                f"m={self.size}{bilateral} title={self.title!r}>")


def load(path, isolate=False):
    """Reads an FCLIB HDF5 file: a LocalProblem (/fclib_local) or a
    GlobalProblem (/fclib_global). Raises FileNotFoundError for a missing
    file and fcsolve.FclibError (an OSError naming the file and dataset) for
    a malformed one. The stored /solution and /guesses are read by
    load_solution() and load_guesses().

    isolate=True: for files from untrusted sources. The HDF5 library itself
    can crash or allocate without bound on corrupt metadata (fcsolve's own
    checks come after it); the file is first read in a separate interpreter
    (about 0.2 s), and a reader that dies raises FclibError here instead of
    taking this process down."""
    path = os.fspath(path)
    if not os.path.exists(path):
        raise FileNotFoundError(errno.ENOENT, os.strerror(errno.ENOENT), path)
    if isolate:
        _probe_in_child(path)
    data = _fcsolve.load(path)
    if isinstance(data, _fcsolve.LocalProblemData):
        return LocalProblem._wrap(data)
    return GlobalProblem._wrap(data)


_PROBE = """
import json, resource, sys
resource.setrlimit(resource.RLIMIT_AS, (4 << 30, 4 << 30))
from fcsolve import _fcsolve
try:
    _fcsolve.load(sys.argv[1])
except _fcsolve.FclibError as e:
    print(json.dumps(dict(dataset=e.dataset, message=str(e))))
    sys.exit(2)
except BaseException as e:
    print(json.dumps(dict(dataset="", message=f"{sys.argv[1]}: {type(e).__name__}: {e}")))
    sys.exit(2)
"""


def _probe_in_child(path):
    """Reads `path` in a child interpreter with a 4 GB memory limit. A clean
    failure there is raised here as the same FclibError, without reading the
    file in this process; a child that dies raises FclibError too."""
    import json
    import subprocess
    import sys

    package_root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        p for p in (package_root, os.environ.get("PYTHONPATH", "")) if p))
    child = subprocess.run([sys.executable, "-c", _PROBE, path], env=env,
                           capture_output=True, text=True)
    if child.returncode == 0:
        return
    if child.returncode == 2 and child.stdout.strip():
        report = json.loads(child.stdout.strip().splitlines()[-1])
        dataset, message = report["dataset"], report["message"]
    else:
        how = (f"signal {-child.returncode}" if child.returncode < 0
               else f"exit status {child.returncode}")
        dataset, message = "", f"{path}: corrupt HDF5 metadata: the HDF5 library died reading it ({how})"
    exc = _fcsolve.FclibError(message)
    exc.path, exc.dataset = path, dataset
    raise exc


def _solution_arrays(solution, problem, what):
    """(r, u, v, l) from a Result, a mapping with keys r, u, v, l (or
    multipliers), or an array r; checked against the problem's sizes."""
    if isinstance(solution, Result):
        r, u, v, l = solution.r, solution.u, solution.v, solution.multipliers
    elif isinstance(solution, Mapping):
        unknown = set(solution) - {"r", "u", "v", "l", "multipliers"}
        if unknown:
            raise _invalid(what, f"unknown keys {sorted(unknown)} (expected r, u, v, l)")
        r, u, v = solution.get("r"), solution.get("u"), solution.get("v")
        l = solution.get("l", solution.get("multipliers"))
    else:
        r, u, v, l = solution, None, None, None
    sizes = {"r": problem.size, "u": problem.size}
    if isinstance(problem, GlobalProblem):
        sizes["v"] = problem.num_dofs
        sizes["l"] = 0 if problem.b is None else problem.b.size
    arrays = []
    for name, x in zip("ruvl", (r, u, v, l)):
        if x is not None:
            if name not in sizes:
                raise _invalid(what, f"{name} is for global problems only")
            if np.ndim(x) != 1 or len(x) != sizes[name]:
                raise _invalid(what, f"{name} must have {sizes[name]} entries, got shape {np.shape(x)}")
        arrays.append(x)
    return tuple(arrays)


def save(path, problem, solution=None, guesses=None):
    """Writes `problem` to a new FCLIB HDF5 file (replacing any file at path),
    with an optional /solution and /guesses.

    solution: an fcsolve.Result, a dict with keys r, u, v, l (any may be
    absent), or the array r alone; guesses: a list of the same. Matrices are
    written in compressed-column form (nz = -1)."""
    path = os.fspath(path)
    if not isinstance(problem, _Problem):
        raise TypeError("problem must be an fcsolve.LocalProblem or fcsolve.GlobalProblem")
    arrays = None if solution is None else _solution_arrays(solution, problem, "solution")
    guess_arrays = [_solution_arrays(g, problem, "guesses") for g in (guesses or [])]
    problem._data.save(path)
    if arrays is not None:
        _fcsolve.write_solution(path, arrays)
    if guess_arrays:
        _fcsolve.write_guesses(path, guess_arrays)


def load_solution(path):
    """The /solution group of an FCLIB file as a dict {r, u, v, l} (absent
    vectors are None), or None if the file has none."""
    return _fcsolve.read_solution(os.fspath(path))


def load_guesses(path):
    """The /guesses groups of an FCLIB file: a list of dicts {r, u, v, l}."""
    return _fcsolve.read_guesses(os.fspath(path))


def _interior_point_tool(name):
    """A compiled function of the interior-point family (existence check,
    diagnostics), present when the library has that family."""
    try:
        return getattr(_fcsolve, name)
    except AttributeError:
        raise NotImplementedError(
            f"{name} needs the interior-point family (fcsolve/ipm), which this build of "
            "fcsolve does not have") from None


def check_existence(problem, tol=1e-10, max_time=None, to_optimum=False):
    """Numerical check of the existence assumption (Acary & Cadoux 2013;
    Acary, Cadoux, Lemarechal & Malick 2011, Thm 3.3): is there v with
    H^T v + w strictly inside the dual cones K* (for a LocalProblem: r with
    W r + q inside K*)? If so, the problem has a solution.

    Solves a homogenised second-order-cone program with the interior-point
    method and checks the witness of every iterate directly, stopping at the
    first certified one (to_optimum=True: on to the program's optimum x*,
    the statistic of the talk's validation). Returns a dict: slater (True: a solution exists),
    verdict ('solution-exists' or 'not-established'), x_star (optimal value
    of the program, > 0 iff the assumption holds; its size depends on the
    program's form, e.g. a LocalProblem with a dense W runs the reduced
    form, the verdict does not; where the program stopped at a certified
    witness, check_status 'certified', x_star is that iterate's), witness
    (v, or r for a local problem), witness_norm, margin (min over contacts
    of u_N - mu ||u_T|| at the witness), and the program's own
    check_error, check_status, check_iterations, and check_program:
    'global-form' for a GlobalProblem; for a LocalProblem
    'cholesky-form' (sparse W: H^T replaced by a sparse Cholesky factor of
    W + eps I, FC/I's metric), 'reduced-form' (dense W) or 'w-form' (H^T = W,
    where that factorisation failed). max_time (seconds, None: unlimited)
    bounds the check from its start, honoured between the program's
    iterations: a program cut by it has check_status 'timeout' and, unless
    the witness it had reached is certified, verdict 'not-established'. Needs
    friction cones (d = 2 or 3). NotImplementedError if this build lacks the
    interior-point family."""
    if not isinstance(problem, _Problem):
        raise TypeError("problem must be an fcsolve.LocalProblem or fcsolve.GlobalProblem")
    # the C++ check refuses a max_time that is not positive (fcsolve.UsageError)
    max_time = float("inf") if max_time is None else float(max_time)
    return _interior_point_tool("check_existence")(problem._data, tol, max_time, bool(to_optimum))
