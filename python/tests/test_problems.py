"""Problems from Python: FCLIB round trips, the error against fcref, views,
validation of bad input, the reduction and the summary."""

import gc
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as sla

import fcsolve
from conftest import FCREF, ROOT, all_files, data_file


def random_reaction(problem, seed=0):
    """A deterministic r with a mix of contacts inside, on and outside K."""
    rng = np.random.default_rng(seed)
    return rng.standard_normal(problem.size) * np.abs(problem.q if hasattr(problem, "q") else
                                                      problem.w).mean()


def one_contact(q=(-1.0, 0.1, 0.0), mu=0.5, W=None):
    return fcsolve.LocalProblem(sp.identity(3) if W is None else W, np.array(q), [mu])


def test_the_package_holds_every_module_of_the_source_tree():
    """The build tree (PYTHONPATH=build/python) or the installed wheel has
    every module of python/fcsolve, subpackages included."""
    source = ROOT / "python" / "fcsolve"
    package = Path(fcsolve.__file__).parent
    missing = [str(p.relative_to(source)) for p in source.rglob("*.py")
               if not (package / p.relative_to(source)).exists()]
    assert not missing, f"{package} lacks {missing}"


# ---------------------------------------------------------------- loading, views

def test_load_local_gives_zero_copy_read_only_views():
    P = fcsolve.load(data_file("Capsules-i101-404.hdf5"))
    assert isinstance(P, fcsolve.LocalProblem)
    assert (P.d, P.num_contacts, P.size) == (3, 225, 675)
    assert isinstance(P.W, sp.csc_matrix) and P.W.shape == (675, 675)
    assert P.W is P.W  # built once
    raw = P._data.W
    assert np.shares_memory(P.W.data, raw[0]) and np.shares_memory(P.W.indices, raw[1])
    assert np.shares_memory(P.q, P._data.q)
    for array in (P.q, P.mu, P.W.data, P.W.indices):
        assert not array.flags.writeable
        with pytest.raises(ValueError):
            array[0] = 1.0


def test_views_keep_the_problem_alive():
    q = fcsolve.load(data_file("FC3D_Example1.hdf5")).q
    W = fcsolve.load(data_file("FC3D_Example1.hdf5")).W
    gc.collect()
    assert np.isfinite(q).all() and q.size == 9
    assert np.isfinite((W @ q)).all()


def test_load_global(fcref):
    path = data_file("GFC3D_Example1.hdf5")
    G = fcsolve.load(path)
    ref = fcref.load(str(path))
    assert isinstance(G, fcsolve.GlobalProblem)
    assert (G.num_dofs, G.size, G.num_contacts) == (3, 3, 1)
    assert abs(G.M - ref["M"]).max() == 0 and abs(G.H - ref["H"]).max() == 0
    np.testing.assert_array_equal(G.f, ref["f"])
    np.testing.assert_array_equal(G.w, ref["w"])
    assert G.G is None and G.b is None


@pytest.mark.parametrize("kind", ["local", "global"])
def test_every_file_matches_fcref(fcref, kind):
    """Same matrices as the independent reader, on every file."""
    for path in all_files(kind):
        P, ref = fcsolve.load(path), fcref.load(str(path))
        names = ["W"] if kind == "local" else ["M", "H"]
        for name in names:
            assert abs(getattr(P, name) - ref[name]).max() == 0, (path.name, name)
        np.testing.assert_array_equal(P.mu, ref["mu"])


# ---------------------------------------------------------------- error

@pytest.mark.parametrize("seed", [0, 1])
def test_local_error_agrees_with_fcref(fcref, seed):
    files = all_files("local")
    assert len(files) >= 3
    for path in files:
        P, ref = fcsolve.load(path), fcref.load(str(path))
        for r in (np.zeros(P.size), random_reaction(P, seed)):
            assert P.error(r) == pytest.approx(fcref.error(ref, r), rel=1e-10, abs=1e-300), path.name


def test_global_error_agrees_with_fcref(fcref):
    files = [p for p in all_files("global") if "G" not in fcref.load(str(p))]
    assert len(files) >= 2
    rng = np.random.default_rng(3)
    for path in files:
        G, ref = fcsolve.load(path), fcref.load(str(path))
        r = rng.standard_normal(G.size)
        v = rng.standard_normal(G.num_dofs)
        assert G.error(r) == pytest.approx(fcref.error(ref, r), rel=1e-8), path.name
        assert G.error(r, v) == pytest.approx(fcref.error(ref, r, v), rel=1e-8), path.name


def test_error_report_and_closed_form():
    # W = I, q = (-1, 0.1, 0), mu = 0.5: r = (1, -0.1, 0) sticks (u = 0): error 0
    P = one_contact()
    assert P.error([1.0, -0.1, 0.0]) == pytest.approx(0.0, abs=1e-15)
    report = P.error_report(np.zeros(3))
    # r = 0: u~ = q + (mu ||q_T||, 0, 0), F = -P_K(-u~) -> hand computed below
    u_tilde = np.array([-1.0 + 0.5 * 0.1, 0.1, 0.0])
    z = -u_tilde  # = (0.95, -0.1, 0) is inside K (0.1 <= 0.5 * 0.95): P_K(z) = z
    assert report["error"] == pytest.approx(np.linalg.norm(z) / np.linalg.norm([-1.0, 0.1, 0.0]))
    assert report["worst_contact"] == 0
    assert set(report) == {"error", "siconos_error", "absolute", "max_contact", "worst_contact"}


def test_error_rejects_a_wrong_reaction():
    P = one_contact()
    with pytest.raises(fcsolve.InvalidProblemError) as e:
        P.error(np.zeros(4))
    assert e.value.field == "r"
    with pytest.raises(fcsolve.InvalidProblemError):
        P.error(np.zeros((3, 1)))


# ---------------------------------------------------------------- save / load

def assert_same_problem(a, b):
    assert type(a) is type(b) and a.d == b.d and a.title == b.title
    names = ["W", "q", "mu"] if isinstance(a, fcsolve.LocalProblem) else ["M", "H", "f", "w", "mu"]
    for name in names:
        x, y = getattr(a, name), getattr(b, name)
        if sp.issparse(x):
            assert (x != y).nnz == 0, name
        else:
            np.testing.assert_array_equal(x, y, err_msg=name)


@pytest.mark.parametrize("name", ["Capsules-i101-404.hdf5", "FC3D_Example1.hdf5",
                                  "GFC3D_Example1.hdf5", "LMGC_GlobalFrictionContactProblem00046.hdf5"])
def test_round_trip(tmp_path, name):
    P = fcsolve.load(data_file(name))
    path = tmp_path / "copy.hdf5"
    rng = np.random.default_rng(7)
    r, u = rng.standard_normal(P.size), rng.standard_normal(P.size)
    solution = {"r": r, "u": u}
    if isinstance(P, fcsolve.GlobalProblem):
        solution["v"] = rng.standard_normal(P.num_dofs)
    fcsolve.save(path, P, solution=solution, guesses=[{"r": r}, 2 * r])
    Q = fcsolve.load(path)
    assert_same_problem(P, Q)
    stored = fcsolve.load_solution(path)
    for key, value in solution.items():
        np.testing.assert_array_equal(stored[key], value)
    guesses = fcsolve.load_guesses(path)
    assert len(guesses) == 2
    np.testing.assert_array_equal(guesses[0]["r"], r)
    np.testing.assert_array_equal(guesses[1]["r"], 2 * r)
    assert guesses[0]["u"] is None
    if FCREF is not None:  # the file is valid FCLIB for an independent reader
        ref = FCREF.load(str(path))
        key = "W" if isinstance(P, fcsolve.LocalProblem) else "M"
        assert abs(ref[key] - getattr(P, key)).max() == 0


def test_round_trip_of_a_problem_built_from_numpy(tmp_path):
    W = np.array([[2.0, 0.1, 0], [0.3, 1.0, 0], [0, 0, 1.0]])  # not symmetric: accepted
    P = fcsolve.LocalProblem(W, [-1.0, 0.2, 0.0], 0.3, title="mine", description="d",
                             math_info="m")
    fcsolve.save(tmp_path / "p.hdf5", P)
    Q = fcsolve.load(tmp_path / "p.hdf5")
    assert_same_problem(P, Q)
    assert (Q.description, Q.math_info) == ("d", "m")
    assert fcsolve.load_solution(tmp_path / "p.hdf5") is None
    assert fcsolve.load_guesses(tmp_path / "p.hdf5") == []


def test_save_rejects_a_solution_of_the_wrong_size(tmp_path):
    P = one_contact()
    with pytest.raises(fcsolve.InvalidProblemError, match="r must have 3"):
        fcsolve.save(tmp_path / "p.hdf5", P, solution=np.zeros(4))
    with pytest.raises(fcsolve.InvalidProblemError, match="global problems only"):
        fcsolve.save(tmp_path / "p.hdf5", P, solution={"r": np.zeros(3), "v": np.zeros(3)})
    with pytest.raises(TypeError):
        fcsolve.save(tmp_path / "p.hdf5", {"W": 1})


def test_bad_files(tmp_path):
    with pytest.raises(FileNotFoundError):
        fcsolve.load(tmp_path / "missing.hdf5")
    text = tmp_path / "text.hdf5"
    text.write_text("not hdf5")
    with pytest.raises(fcsolve.FclibError) as e:
        fcsolve.load(text)
    assert isinstance(e.value, OSError) and e.value.path == str(text)
    with pytest.raises(fcsolve.FclibError):
        fcsolve.save(tmp_path / "no-such-dir" / "p.hdf5", one_contact())


# ---------------------------------------------------------------- construction and validation

def test_construction_copies_and_does_not_modify_the_input():
    W = sp.random(6, 6, density=0.5, random_state=1, format="coo") + sp.identity(6)
    q = np.array([-1.0, 0.1, 0.2, 0.5, 0.0, 0.0])
    mu = np.array([0.3, 0.4])
    W_before, q_before = W.toarray(), q.copy()
    P = fcsolve.LocalProblem(W, q, mu)
    np.testing.assert_array_equal(W.toarray(), W_before)
    np.testing.assert_array_equal(q, q_before)
    assert not np.shares_memory(P.q, q)
    q[0] = 99.0  # the problem holds its own copy
    assert P.q[0] == -1.0
    assert abs(P.W - sp.csc_matrix(W_before)).max() == 0


def test_accepted_inputs():
    # dense, CSR, integer dtypes, lists, a scalar mu, an unsymmetric W
    for W in (np.eye(3), sp.csr_matrix(np.eye(3)), np.eye(3, dtype=np.int64), [[1, 0, 0], [0, 1, 0], [0, 0, 1]]):
        P = fcsolve.LocalProblem(W, [-1, 0, 0], 0.5)
        assert P.W.dtype == np.float64 and P.mu.tolist() == [0.5]
    U = np.array([[1.0, 0.5, 0], [0, 1.0, 0], [0, 0, 1.0]])
    info = fcsolve.LocalProblem(U, [-1, 0, 0], 0.5).info()
    assert info["asymmetry_W"] > 0.3
    assert fcsolve.LocalProblem(np.eye(2), [-1, 0.5], [0.2], d=2).d == 2
    assert fcsolve.LocalProblem(np.eye(2), [-1, 0.5], [0, 0], d=1).num_contacts == 2


BAD_LOCAL = [
    # (W, q, mu, d, field, message fragment)
    (np.eye(4), [-1, 0, 0], [0.5], 3, "W", "expected 3 x 3"),
    (np.ones((3, 2)), [-1, 0, 0], [0.5], 3, "W", "square"),
    (np.ones(3), [-1, 0, 0], [0.5], 3, "W", "2-D"),
    (np.eye(3), [-1, 0, 0, 0], [0.5], 3, "q", "expected 3 entries"),
    (np.eye(3), [[-1, 0, 0]], [0.5], 3, "q", "1-D"),
    (np.eye(3), [-1, 0, 0], [0.5, 0.5], 3, "mu", "expected 1 entries"),
    (np.eye(3), [-1, np.nan, 0], [0.5], 3, "q", "non-finite"),
    (np.diag([1, np.inf, 1]), [-1, 0, 0], [0.5], 3, "W", "non-finite"),
    (np.eye(3), [-1, 0, 0], [-0.5], 3, "mu", "negative"),
    (np.eye(3), [-1, 0, 0], [np.nan], 3, "mu", "non-finite"),
    (np.eye(3) * 1j, [-1, 0, 0], [0.5], 3, "W", "dtype complex"),
    (np.eye(3), np.array([-1, 0, 0], dtype=complex), [0.5], 3, "q", "dtype complex"),
    (np.eye(3), ["a", "b", "c"], [0.5], 3, "q", "dtype"),
    (np.eye(3), [-1, 0, 0], "0.5", 3, "mu", "dtype"),
    (np.eye(3, dtype=bool), [-1, 0, 0], [0.5], 3, "W", "dtype bool"),
    (np.eye(3), [-1, 0, 0], [0.5], 4, "spacedim", "1, 2 or 3"),
    (np.eye(3), [-1, 0, 0], [0.5], 2.5, "d", "integer"),
    (np.zeros((0, 0)), [], [], 3, "W", "empty"),
    # the matrix sets the size: the vector of the wrong length is blamed
    (np.eye(6), [-1, 0, 0, 0, 0], 0.5, 3, "q", "expected 6 entries"),
    (np.eye(3), [-1, 0, 0], [0.5], True, "d", "integer"),
]


@pytest.mark.parametrize("W, q, mu, d, field, fragment", BAD_LOCAL)
def test_bad_local_input_raises_a_clear_value_error(W, q, mu, d, field, fragment):
    with pytest.raises(ValueError) as e:
        fcsolve.LocalProblem(W, q, mu, d=d)
    assert isinstance(e.value, fcsolve.InvalidProblemError)
    assert e.value.field == field, str(e.value)
    assert fragment in str(e.value) and str(e.value).startswith(field + ":")


def global_parts(n=3):
    return dict(M=sp.identity(n) * 2.0, H=sp.identity(n), f=np.zeros(n) - 1.0, w=np.zeros(n), mu=[0.3])


@pytest.mark.parametrize("change, field", [
    (dict(M=sp.identity(4)), "M"),
    (dict(H=sp.identity(3).tocsr()[:, :2]), "H"),
    (dict(H=np.ones((2, 3))), "H"),
    (dict(f=[1.0, np.nan, 0.0]), "f"),
    (dict(w=[0, 0]), "w"),
    (dict(mu=[-1.0]), "mu"),
    (dict(M=sp.identity(3) * 1j), "M"),
    (dict(G=np.ones((3, 1))), "b"),
    (dict(b=[1.0]), "G"),
    (dict(G=np.ones((3, 2)), b=[1.0]), "G"),
])
def test_bad_global_input_raises_a_clear_value_error(change, field):
    parts = global_parts()
    parts.update(change)
    with pytest.raises(fcsolve.InvalidProblemError) as e:
        fcsolve.GlobalProblem(**parts)
    assert e.value.field == field, str(e.value)


def test_short_f_is_blamed_not_M():
    parts = global_parts(5)
    parts.update(H=sp.identity(5).tocsc()[:, :3], w=np.zeros(3), f=np.ones(4))
    with pytest.raises(fcsolve.InvalidProblemError) as e:
        fcsolve.GlobalProblem(**parts)
    assert e.value.field == "f" and "expected 5 entries" in str(e.value), str(e.value)


def test_error_of_a_non_finite_r_raises():
    P = fcsolve.LocalProblem(np.eye(3), [-1.0, 0.2, 0.0], [0.5])
    for bad in ([np.nan, 0, 0], [0, np.inf, 0]):
        with pytest.raises(fcsolve.InvalidProblemError) as e:
            P.error(bad)
        assert e.value.field == "r" and "non-finite" in str(e.value)
        with pytest.raises(fcsolve.InvalidProblemError):
            P.error_report(bad)


@pytest.mark.parametrize("options", [dict(tol="1e-8"), dict(tol=True), dict(max_time="1"),
                                     dict(max_iter=2.5), dict(max_iter=True)])
def test_solve_options_of_the_wrong_type_name_the_option(options):
    P = fcsolve.LocalProblem(np.eye(3), [-1.0, 0.2, 0.0], [0.5])
    with pytest.raises(TypeError) as e:
        fcsolve.solve(P, "nsgs", **options)
    assert next(iter(options)) in str(e.value)


def test_global_with_bilateral_constraints():
    parts = global_parts()
    G = sp.csc_matrix(np.array([[1.0], [0.0], [0.0]]))
    P = fcsolve.GlobalProblem(G=G, b=[0.5], **parts)
    assert P.G.shape == (3, 1) and P.b.tolist() == [0.5]
    L = P.reduce()
    assert isinstance(L, fcsolve.LocalProblem) and L.size == 3


# ---------------------------------------------------------------- reduction, summary

@pytest.mark.parametrize("name", ["GFC3D_Example1.hdf5", "Box_Stacks-i0035-31-0.hdf5",
                                  "LMGC_GlobalFrictionContactProblem00046.hdf5"])
def test_reduce_matches_scipy(name):
    G = fcsolve.load(data_file(name))
    L = G.reduce()
    M, H = G.M.tocsc(), G.H.tocsc()
    solve = sla.factorized(M)
    W = H.T @ np.column_stack([solve(H[:, j].toarray().ravel()) for j in range(H.shape[1])])
    q = H.T @ solve(np.asarray(G.f)) + G.w
    assert np.abs(L.W.toarray() - W).max() <= 1e-8 * np.abs(W).max()
    np.testing.assert_allclose(L.q, q, rtol=1e-8, atol=1e-12 * np.abs(q).max())
    # the reduced problem scores a reaction as the global one does
    r = random_reaction(L, 5)
    assert L.error(r) == pytest.approx(G.error(r), rel=1e-6)


def test_info():
    P = fcsolve.load(data_file("Capsules-i101-404.hdf5"))
    info = P.info()
    assert info["kind"] == "local" and info["nc"] == 225 and info["m"] == 675
    assert info["nnz_W"] == P.W.nnz and info["mu_min"] == info["mu_max"] == 0.7
    assert info["asymmetry_W"] > 0  # Capsules' W is not symmetric (real data)
    G = fcsolve.load(data_file("LMGC_GlobalFrictionContactProblem00046.hdf5")).info()
    assert G["kind"] == "global" and G["n"] == 162 and G["asymmetry_M"] > 0
    assert "LocalProblem" in repr(P)


# ---------------------------------------------------------------- existence check, diagnostics

needs_checks = pytest.mark.skipif(
    not hasattr(fcsolve._fcsolve, "check_existence"),
    reason="this build has no existence check / diagnostics (interior-point family absent)")


@needs_checks
@pytest.mark.parametrize("name", ["Capsules-i101-404.hdf5", "Box_Stacks-i0035-31-0.hdf5",
                                  "CubeH8.hdf5"])
def test_existence_check_gives_a_certificate(name):
    P = fcsolve.load(data_file(name))
    rep = fcsolve.check_existence(P)
    assert rep["slater"] and rep["verdict"] == "solution-exists" and rep["x_star"] > 0
    # the witness is a certificate, checked here: u = H^T v + w (W r + q) is
    # strictly inside every dual cone K* = {u_N >= mu ||u_T||}
    witness = rep["witness"]
    if isinstance(P, fcsolve.GlobalProblem):
        u = P.H.T @ witness + P.w
    else:
        u = P.W @ witness + P.q
    U = u.reshape(-1, 3)
    margin = U[:, 0] - P.mu * np.linalg.norm(U[:, 1:], axis=1)
    assert margin.min() > 0
    assert margin.min() == pytest.approx(rep["margin"], rel=1e-6)
    expected = "global-form" if isinstance(P, fcsolve.GlobalProblem) else "cholesky-form"
    assert rep["check_program"] == expected  # these W are sparse
    assert rep["witness_norm"] == pytest.approx(np.linalg.norm(witness))


@needs_checks
def test_existence_check_honours_max_time():
    # Capsules (675 columns): cut at 1 us the program reports a timeout and
    # claims a solution only with a certified witness; max_time must be > 0
    P = fcsolve.load(data_file("Capsules-i101-404.hdf5"))
    rep = fcsolve.check_existence(P, max_time=1e-6)
    assert rep["check_status"] == "timeout"
    assert (rep["verdict"] == "solution-exists") == (rep["margin"] > 0)
    full = fcsolve.check_existence(P, max_time=60)
    assert full["check_status"] != "timeout" and full["verdict"] == "solution-exists"
    # to_optimum: on past the first certified witness to x*, same verdict
    optimum = fcsolve.check_existence(P, to_optimum=True)
    assert optimum["check_status"] not in ("certified", "timeout"), optimum  # Capsules: stalled
    assert optimum["verdict"] == "solution-exists"
    assert optimum["check_iterations"] >= full["check_iterations"] and optimum["x_star"] > 0
    for bad in (0, -1.0, float("nan")):
        with pytest.raises(ValueError, match="max_time"):
            fcsolve.check_existence(P, max_time=bad)


@needs_checks
def test_existence_check_without_a_slater_point():
    # W has no normal coupling: u_N = q_N = -1 for every r, never inside K*
    P = fcsolve.LocalProblem(np.diag([0.0, 1.0, 1.0]), [-1.0, 0.0, 0.0], [0.5])
    rep = fcsolve.check_existence(P)
    assert not rep["slater"] and rep["verdict"] == "not-established"
    with pytest.raises(fcsolve.UsageError, match="friction"):
        fcsolve.check_existence(fcsolve.LocalProblem(np.eye(2), [1.0, 2.0], [0, 0], d=1))
    with pytest.raises(TypeError):
        fcsolve.check_existence("not a problem")


@needs_checks
def test_diagnostics():
    G = fcsolve.load(data_file("Box_Stacks-i0035-31-0.hdf5"))
    d = G.diagnostics()
    assert d["contact_ratio"] == pytest.approx(G.size / G.num_dofs)
    assert d["rank_H"] == d["m"] == G.size  # H has full column rank here
    W = G.reduce().W
    eig = np.linalg.eigvalsh(((W + W.T) / 2).toarray())
    assert d["lambda_min_W"] == pytest.approx(eig.min(), rel=1e-8)
    assert d["lambda_max_W"] == pytest.approx(eig.max(), rel=1e-8)
    assert d["cond_W"] == pytest.approx(eig.max() / eig.min(), rel=1e-8)
    P = fcsolve.load(data_file("Capsules-i101-404.hdf5"))
    d = P.diagnostics()
    assert 0 < d["rank_W"] < d["m"] == P.size  # more contact unknowns than dofs behind W
    # a sparse W's extreme eigenvalues come from Lanczos; the rank below m
    # makes lambda_min 0
    eig = np.linalg.eigvalsh(((P.W + P.W.T) / 2).toarray())
    assert d["lambda_max_W"] == pytest.approx(eig.max(), rel=1e-8)
    assert d["lambda_min_W"] == 0 and d["cond_W"] == float("inf")
    assert d["asymmetry_W"] == pytest.approx(P.info()["asymmetry_W"])
    assert "contact_ratio" not in d


@pytest.mark.skipif(hasattr(fcsolve._fcsolve, "check_existence"),
                    reason="this build has the interior-point family")
def test_checks_say_when_the_interior_point_family_is_absent():
    with pytest.raises(NotImplementedError, match="interior-point"):
        fcsolve.check_existence(one_contact())
    with pytest.raises(NotImplementedError, match="interior-point"):
        one_contact().diagnostics()
