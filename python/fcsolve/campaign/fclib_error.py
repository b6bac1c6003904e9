"""The campaign's own FCLIB reader and error measure (numpy, scipy, h5py).

A campaign judges every run, fcsolve's and the peers', by recomputing the error
of the solution file it returned, independently of the solver's own claim.
The measure is the FCLIB relative natural-map error (Acary, Bremond & Huber
2018, the FCLIB error; Acary 2025 (talk), eq. (20); docs/references.md):

    u        = W r + q                  (FC/II)   or   u = H^T v + w  (FC/I)
    u~^a     = u^a + (mu_a ||u_T^a||, 0, ...)      (De Saxce's modified velocity)
    F_nat^a  = r^a - P_{K_a}(r^a - u~^a),  K_a = {||r_T|| <= mu_a r_N}
    error    = ||F_nat||_2 / ||q||_2     (1 instead of ||q|| when q = 0)

For FC/I, q is the reduced problem's q = H^T M^-1 f + w (the free velocity),
so a global problem and its reduction score alike, and the error is the larger
of that and the equilibrium residual ||M v - H r - G l - f|| / max(||f||,
||M v||, ||H r||, ||G l||) (with bilateral constraints G^T v + b = 0 also
||G^T v + b|| / max(||b||, ||G||_F ||v||), a scale that does not vanish
with the residual when b = 0). d = 3 and 2 are Coulomb cones, d = 1
is frictionless (K = R+, u~ = u).
"""
import functools
import os

import h5py
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as sla


def _scalar(group, name):
    return int(np.asarray(group[name]).ravel()[0])


def read_matrix(group):
    """An FCLIB matrix group (m, n, nz, p, i, x) as a CSR matrix.

    nz >= 0: triplets. fclib.h documents p = rows, i = columns, but the files
    written by Siconos and LMGC90 use CSparse's i = rows, p = columns; read the
    files' way, and the documented way only when the indices do not fit.
    nz = -1: compressed columns; nz = -2: compressed rows.
    """
    m, n, nz = _scalar(group, "m"), _scalar(group, "n"), _scalar(group, "nz")
    x = np.asarray(group["x"], dtype=float)
    i = np.asarray(group["i"], dtype=np.int64)
    p = np.asarray(group["p"], dtype=np.int64)
    if nz >= 0:
        rows, cols, x = i[:nz], p[:nz], x[:nz]

        def fits(a, b):
            return nz == 0 or (a.min() >= 0 and b.min() >= 0 and a.max() < m and b.max() < n)

        if not fits(rows, cols):
            rows, cols = cols, rows
        if not fits(rows, cols):
            raise ValueError(f"{group.name}: triplet indices do not fit a {m} x {n} matrix")
        return sp.coo_matrix((x, (rows, cols)), shape=(m, n)).tocsr()  # sums duplicates
    if nz in (-1, -2):
        outer = n if nz == -1 else m
        nnz = int(p[outer])
        cls = sp.csc_matrix if nz == -1 else sp.csr_matrix
        return cls((x[:nnz], i[:nnz], p[:outer + 1]), shape=(m, n)).tocsr()
    raise ValueError(f"{group.name}: unknown FCLIB storage nz = {nz}")


class Problem:
    """An FCLIB problem, with what the error needs cached (reduced ||q||)."""

    def __init__(self, path):
        self.path = path
        with h5py.File(path, "r") as f:
            if "fclib_local" in f:
                g = f["fclib_local"]
                self.kind = "local"
                self.W = read_matrix(g["W"])
                self.q = np.asarray(g["vectors/q"], dtype=float)
            elif "fclib_global" in f:
                g = f["fclib_global"]
                self.kind = "global"
                self.M, self.H = read_matrix(g["M"]), read_matrix(g["H"])
                self.f = np.asarray(g["vectors/f"], dtype=float)
                self.w = np.asarray(g["vectors/w"], dtype=float)
                self.G = read_matrix(g["G"]) if "G" in g else None
                self.b = np.asarray(g["vectors/b"], dtype=float) if self.G is not None else None
            else:
                raise ValueError(f"{path}: neither /fclib_local nor /fclib_global")
            self.mu = np.asarray(g["vectors/mu"], dtype=float)
            self.d = _scalar(g, "spacedim")
        self._q_norm = None

    @property
    def nc(self):
        return self.mu.size

    @property
    def m(self):
        return self.d * self.nc

    @property
    def n(self):
        """Degrees of freedom (global problems), None for local ones."""
        return self.M.shape[0] if self.kind == "global" else None

    def free_velocity_norm(self):
        """||q|| of the reduced problem: H^T v0 + w with M v0 = f (and G^T v0 + b = 0)."""
        if self._q_norm is None:
            if self.kind == "local":
                self._q_norm = float(np.linalg.norm(self.q))
            else:
                n = self.M.shape[0]
                if self.G is None:
                    v0 = sla.splu(self.M.tocsc()).solve(self.f)
                else:
                    K = sp.bmat([[self.M, -self.G], [self.G.T, None]], format="csc")
                    v0 = sla.splu(K).solve(np.concatenate([self.f, -self.b]))[:n]
                self._q_norm = float(np.linalg.norm(self.H.T @ v0 + self.w))
        return self._q_norm


def project_cone(z, mu):
    """Row-wise Euclidean projection of z (nc x d) onto {||z_T|| <= mu z_N}.

    Closed form for a second-order cone of aperture mu (Acary & Brogliato 2008,
    sec. 12.4): inside -> z, in the polar cone -> 0, else onto the boundary
    ray through the tangential direction of z. d = 1: projection onto R+.
    """
    if z.shape[1] == 1:
        return np.maximum(z, 0.0)
    zn, zt = z[:, 0], z[:, 1:]
    nt = np.linalg.norm(zt, axis=1)
    out = z.copy()
    inside = (nt <= mu * zn) & (zn >= 0)
    polar = ~inside & (mu * nt <= -zn)
    boundary = ~(inside | polar)
    out[polar] = 0.0
    a = (zn[boundary] + mu[boundary] * nt[boundary]) / (1.0 + mu[boundary] ** 2)
    out[boundary, 0] = a
    out[boundary, 1:] = (mu[boundary] * a / nt[boundary])[:, None] * zt[boundary]
    return out


def natural_map_norm(r, u, mu, d):
    """||F_nat(r)||_2 over all contacts."""
    R, U = r.reshape(-1, d), u.reshape(-1, d).copy()
    if d > 1:
        U[:, 0] += mu * np.linalg.norm(U[:, 1:], axis=1)  # u~ = u + g(u)
    return float(np.linalg.norm(R - project_cone(R - U, mu)))


def _relative(numerator, *scales):
    s = max(scales)
    return numerator / (s if s > 0 else 1.0)


def error(problem, r, v=None, lam=None):
    """FCLIB relative error of a solution (r [, v, lambda]); NaN if not finite."""
    r = np.asarray(r, dtype=float)
    if r.shape != (problem.m,):
        raise ValueError(f"r has {r.size} entries, the problem {problem.m}")
    if not np.all(np.isfinite(r)):
        return float("nan")
    d, mu = problem.d, problem.mu
    if problem.kind == "local":
        u = problem.W @ r + problem.q
        return _relative(natural_map_norm(r, u, mu, d), problem.free_velocity_norm())
    M, H, f = problem.M, problem.H, problem.f
    if v is None:
        if problem.G is not None:
            raise ValueError("a solution of a problem with bilateral constraints needs v")
        v = sla.splu(M.tocsc()).solve(H @ r + f)
    v = np.asarray(v, dtype=float)
    if v.shape != (M.shape[0],) or not np.all(np.isfinite(v)):
        return float("nan")
    comp = _relative(natural_map_norm(r, H.T @ v + problem.w, mu, d), problem.free_velocity_norm())
    Mv, Hr = M @ v, H @ r
    residual, scales = Mv - Hr - f, [np.linalg.norm(f), np.linalg.norm(Mv), np.linalg.norm(Hr)]
    bilateral = 0.0
    if problem.G is not None:
        lam = np.zeros(problem.G.shape[1]) if lam is None else np.asarray(lam, dtype=float)
        Gl, Gtv = problem.G @ lam, problem.G.T @ v
        residual = residual - Gl
        scales.append(np.linalg.norm(Gl))
        bilateral = _relative(np.linalg.norm(Gtv + problem.b),
                              np.linalg.norm(problem.b),
                              sp.linalg.norm(problem.G) * np.linalg.norm(v))
    equil = _relative(float(np.linalg.norm(residual)), *scales)
    return max(comp, equil, bilateral)


def read_solution(path):
    """(r, v, lambda) from a solution file's /solution group (or its root)."""
    with h5py.File(path, "r") as f:
        g = f["solution"] if "solution" in f else f
        get = lambda k: np.asarray(g[k], dtype=float) if k in g else None  # noqa: E731
        return get("r"), get("v"), get("l")


@functools.lru_cache(maxsize=16)
def _cached_problem(path, mtime_ns, size):
    return Problem(path)


def load_problem(path):
    """The problem at `path`, cached per process (keyed by path, mtime and size)."""
    st = os.stat(path)
    return _cached_problem(os.path.abspath(path), st.st_mtime_ns, st.st_size)


def solution_error(problem_path, solution_path):
    """Error of the solution stored at `solution_path` for the problem at `problem_path`."""
    r, v, lam = read_solution(solution_path)
    if r is None:
        raise ValueError(f"{solution_path}: no r in /solution")
    return error(load_problem(problem_path), r, v, lam)
