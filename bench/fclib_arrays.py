"""FCLIB problems as numpy/scipy arrays, and the FCLIB error of a solution.

Used by the benchmark scripts (siconos_runner.py, compare_siconos.py) to read
problems and to judge every solver's output by one yardstick, independently
of the solvers' own reports. Only numpy, scipy and h5py.

Error (Acary, Bremond & Huber 2018, eq. "error"):
    u = W r + q (local)  or  u = H^T v + w (global)
    F = r - P_K(r - (u + g(u))),  g(u) = (mu ||u_T||, 0, ...) per contact
    error = ||F|| / ||q||   (||q|| = 0 -> 1)
For a global problem q is the reduced problem's H^T M^-1 f + w, and the
error is the larger of that and the equilibrium residual
||M v - H r - f|| / max(||f||, ||M v||, ||H r||).
"""
import h5py
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla


def _read_matrix(group):
    m, n, nz = (int(np.asarray(group[k]).reshape(-1)[0]) for k in ("m", "n", "nz"))
    p = np.asarray(group["p"], dtype=np.int64)
    i = np.asarray(group["i"], dtype=np.int64)
    x = np.asarray(group["x"], dtype=float)
    if nz == -1:
        return sp.csc_matrix((x[: p[n]], i[: p[n]], p[: n + 1]), shape=(m, n))
    if nz == -2:
        return sp.csr_matrix((x[: p[m]], i[: p[m]], p[: m + 1]), shape=(m, n)).tocsc()
    if nz < 0:
        raise ValueError(f"unknown FCLIB matrix storage nz={nz}")
    # Triplets: the files written by Siconos and LMGC90 hold row indices in i
    # and column indices in p (CSparse), the reverse of fclib.h's comment;
    # take the documented reading only when the indices do not fit.
    rows, cols = i[:nz], p[:nz]
    if nz and (rows.max() >= m or cols.max() >= n):
        rows, cols = cols, rows
    return sp.coo_matrix((x[:nz], (rows, cols)), shape=(m, n)).tocsc()


def read_problem(path):
    """dict with kind ('local' | 'global'), d, mu and W, q or M, H, f, w."""
    with h5py.File(path, "r") as h5:
        if "fclib_local" in h5:
            g = h5["fclib_local"]
            return dict(kind="local", d=int(np.asarray(g["spacedim"]).reshape(-1)[0]),
                        W=_read_matrix(g["W"]), q=np.asarray(g["vectors/q"], float),
                        mu=np.asarray(g["vectors/mu"], float))
        if "fclib_global" in h5:
            g = h5["fclib_global"]
            out = dict(kind="global", d=int(np.asarray(g["spacedim"]).reshape(-1)[0]),
                       M=_read_matrix(g["M"]), H=_read_matrix(g["H"]),
                       f=np.asarray(g["vectors/f"], float), w=np.asarray(g["vectors/w"], float),
                       mu=np.asarray(g["vectors/mu"], float))
            if "G" in g:
                out["G"] = _read_matrix(g["G"])
                out["b"] = np.asarray(g["vectors/b"], float)
            return out
    raise ValueError(f"{path}: neither /fclib_local nor /fclib_global")


def read_solution(path):
    """(r, v) from /solution (v is None when absent)."""
    with h5py.File(path, "r") as h5:
        g = h5["solution"]
        r = np.asarray(g["r"], float)
        v = np.asarray(g["v"], float) if "v" in g else None
    return r, v


def write_solution(path, r, u=None, v=None):
    with h5py.File(path, "w") as h5:
        g = h5.create_group("solution")
        for name, x in (("r", r), ("u", u), ("v", v)):
            if x is not None:
                g.create_dataset(name, data=np.asarray(x, float))


def _project(z, mu):
    """Rows of z (nc x d, normal first) projected on {||z_T|| <= mu z_N}."""
    zn = z[:, 0]
    nt = np.linalg.norm(z[:, 1:], axis=1)
    out = z.copy()
    polar = mu * nt <= -zn
    boundary = ~((nt <= mu * zn) & (zn >= 0)) & ~polar
    out[polar] = 0.0
    a = (zn[boundary] + mu[boundary] * nt[boundary]) / (1.0 + mu[boundary] ** 2)
    out[boundary, 0] = a
    out[boundary, 1:] = z[boundary, 1:] * (mu[boundary] * a / nt[boundary])[:, None]
    return out


def natural_map_norm(r, u, mu, d):
    R, U = r.reshape(-1, d), u.reshape(-1, d).copy()
    if d == 1:
        return float(np.linalg.norm(R - np.maximum(R - U, 0.0)))
    U[:, 0] += mu * np.linalg.norm(U[:, 1:], axis=1)
    return float(np.linalg.norm(R - _project(R - U, mu)))


class ErrorMeter:
    """Computes the FCLIB error of solutions of one problem (factorises M once)."""

    def __init__(self, problem):
        self.p = problem
        if problem["kind"] == "global":
            if "G" in problem:
                raise NotImplementedError("bilateral constraints (G, b)")
            self._solve = spla.factorized(problem["M"].tocsc())
            P = problem
            self.q = P["H"].T @ self._solve(P["f"]) + P["w"]
        else:
            self.q = problem["q"]
        nq = np.linalg.norm(self.q)
        self.scale = nq if nq > 0 else 1.0

    def error(self, r, v=None):
        P = self.p
        r = np.asarray(r, float)
        if not np.all(np.isfinite(r)) or (v is not None and not np.all(np.isfinite(v))):
            return float("inf")
        if P["kind"] == "local":
            return natural_map_norm(r, P["W"] @ r + P["q"], P["mu"], P["d"]) / self.scale
        M, H, f = P["M"], P["H"], P["f"]
        if v is None:
            v = self._solve(H @ r + f)
        comp = natural_map_norm(r, H.T @ v + P["w"], P["mu"], P["d"]) / self.scale
        Mv, Hr = M @ v, H @ r
        den = max(np.linalg.norm(f), np.linalg.norm(Mv), np.linalg.norm(Hr))
        equil = np.linalg.norm(Mv - Hr - f) / (den if den > 0 else 1.0)
        return float(max(comp, equil))
