"""Writes the hostile corpus: small crafted FCLIB files, one per way a file
can lie, as an attacker or a careless user would write it (issue 15).

    /usr/bin/python3 tests/hostile/make_hostile.py      # rewrites tests/hostile/files

Each file is derived from a bundled problem (examples/data) by one edit.
MANIFEST.json says, per file, which commands must reject it (exit 2, a
message naming the file and the dataset) and the dataset the message names:
`read` = `fcsolve info` and `fcsolve solve` and Python's fcsolve.load;
`solve` = only `fcsolve solve` (the file reads, the problem fails later);
`warm` = `fcsolve solve --warm-start guess`;
`libhdf5` = files on which the HDF5 library itself crashes or allocates
without bound (found by fuzzing, copied from fuzz/regressions): the CLI and
`fcsolve.load(path, isolate=True)` read them in a child process first.
The files are committed; this script documents and regenerates them.
"""
import json
import shutil
from pathlib import Path

import h5py
import numpy as np

HERE = Path(__file__).resolve().parent
OUT = HERE / "files"
DATA = HERE.parents[1] / "examples" / "data"
REGRESSIONS = HERE.parents[1] / "fuzz" / "regressions"
LIBHDF5 = ["libhdf5-local-heap-null-read-1.hdf5", "libhdf5-huge-metadata-alloc-7b02505d.hdf5",
           "libhdf5-runaway-alloc-1.hdf5", "libhdf5-contig-read-null-memcpy.hdf5"]
LOCAL, GLOBAL = "Rover1039.hdf5", "GFC3D_Example1.hdf5"
INT_MAX = 2**31 - 1

CASES = {}


def case(name, dataset, commands="read", source=LOCAL):
    def register(edit):
        CASES[name] = dict(edit=edit, dataset=dataset, commands=commands, source=source)
        return edit
    return register


def replace(f, name, value):
    del f[name]
    f[name] = value


def csc(f, group, m, n, p, i, x):
    """Rewrites a matrix group as compressed columns with the given arrays."""
    for key, value in dict(m=[m], n=[n], nz=[-1], nzmax=[len(x)]).items():
        replace(f, f"{group}/{key}", np.array(value, np.int64 if abs(value[0]) > INT_MAX else np.int32))
    replace(f, f"{group}/p", np.asarray(p, np.int32))
    replace(f, f"{group}/i", np.asarray(i, np.int32))
    replace(f, f"{group}/x", np.asarray(x, float))


# ---- item 1: sizes that overflow 32-bit arithmetic
@case("csc_n_int_max_empty_p", "fclib_local/W")
def _(f):
    csc(f, "fclib_local/W", 12, INT_MAX, [], [], [])


@case("csc_n_int_max_short_p", "fclib_local/W")
def _(f):
    csc(f, "fclib_local/W", 12, INT_MAX, [0, 1, 2], [0, 1], [1.0, 1.0])


@case("int64_size_2_pow_40", "fclib_local/W/n")
def _(f):
    replace(f, "fclib_local/W/n", np.array([2**40], np.int64))


@case("csr_m_int_max", "fclib_local/W")
def _(f):
    csc(f, "fclib_local/W", INT_MAX, 12, [0, 1], [0], [1.0])
    replace(f, "fclib_local/W/nz", np.array([-2], np.int32))


# ---- item 2: arrays where one string is expected
@case("title_array_of_strings", "fclib_local/info/title")
def _(f):
    del f["fclib_local/info/title"]
    f.create_dataset("fclib_local/info/title", data=["a", "bb", "ccc"],
                     dtype=h5py.string_dtype())


@case("math_info_fixed_string_array", "fclib_local/info/math_info")
def _(f):
    if "fclib_local/info/math_info" in f:
        del f["fclib_local/info/math_info"]
    f.create_dataset("fclib_local/info/math_info", data=np.array([b"x" * 40] * 4, dtype="S40"))


# ---- item 3: declared sizes the file cannot fill
@case("q_declares_2_pow_31_entries", "fclib_local/vectors/q")
def _(f):
    del f["fclib_local/vectors/q"]
    f.create_dataset("fclib_local/vectors/q", shape=(2**31,), dtype=float, chunks=(1024,))


@case("W_x_declares_2_pow_30_entries", "fclib_local/W/x")
def _(f):
    del f["fclib_local/W/x"]
    f.create_dataset("fclib_local/W/x", shape=(2**30,), dtype=float, chunks=(4096,))


@case("W_triplet_declares_100000_squared", "fclib_local/W")
def _(f):
    replace(f, "fclib_local/W/m", np.array([100000], np.int32))
    replace(f, "fclib_local/W/n", np.array([100000], np.int32))


@case("global_M_declares_huge", "fclib_global/M", source=GLOBAL)
def _(f):
    replace(f, "fclib_global/M/m", np.array([1 << 30], np.int32))
    replace(f, "fclib_global/M/n", np.array([1 << 30], np.int32))


@case("q_stored_in_external_file", "fclib_local/vectors/q")
def _(f):
    # Right length, but the data lives outside the file: HDF5 would read it
    # from /dev/zero (or any file the user can read, gigabytes of it).
    n = f["fclib_local/vectors/q"].shape[0]
    del f["fclib_local/vectors/q"]
    f.create_dataset("fclib_local/vectors/q", shape=(n,), dtype=float, external=[("/dev/zero", 0, 8 * n)])


# ---- malformed structure and values
@case("p_not_starting_at_0", "fclib_local/W/p")
def _(f):
    csc(f, "fclib_local/W", 12, 12, [1] + [1] * 12, [0], [1.0])


@case("p_decreasing", "fclib_local/W/p")
def _(f):
    csc(f, "fclib_local/W", 12, 12, [0, 2, 1] + [2] * 10, [0, 1], [1.0, 1.0])


@case("p_past_i", "fclib_local/W/i")
def _(f):
    csc(f, "fclib_local/W", 12, 12, [0] + [50] * 12, [0, 1], [1.0, 1.0])


@case("q_two_dimensional", "fclib_local/vectors/q")
def _(f):
    replace(f, "fclib_local/vectors/q", np.ones((3, 4)))


@case("m_is_a_string", "fclib_local/W/m")
def _(f):
    del f["fclib_local/W/m"]
    f.create_dataset("fclib_local/W/m", data="twelve", dtype=h5py.string_dtype())


@case("spacedim_is_a_group", "fclib_local/spacedim")
def _(f):
    del f["fclib_local/spacedim"]
    f.create_group("fclib_local/spacedim")


@case("nan_in_mu", "fclib_local/vectors/mu")
def _(f):
    replace(f, "fclib_local/vectors/mu", np.array([0.5, np.nan, 0.5, 0.5]))


@case("inf_in_q", "fclib_local/vectors/q")
def _(f):
    q = np.ones(12)
    q[5] = -np.inf
    replace(f, "fclib_local/vectors/q", q)


@case("negative_mu", "fclib_local/vectors/mu")
def _(f):
    replace(f, "fclib_local/vectors/mu", np.array([0.5, -0.5, 0.5, 0.5]))


@case("empty_problem", "fclib_local")
def _(f):
    replace(f, "fclib_local/vectors/q", np.zeros(0))
    replace(f, "fclib_local/vectors/mu", np.zeros(0))
    csc(f, "fclib_local/W", 0, 0, [0], [], [])


@case("q_not_multiple_of_d", "fclib_local/vectors/q")
def _(f):
    replace(f, "fclib_local/vectors/q", np.ones(11))


@case("global_f_short", "fclib_global/M", source=GLOBAL)
def _(f):
    n = f["fclib_global/vectors/f"].shape[0]
    replace(f, "fclib_global/vectors/f", np.ones(n - 1))


@case("global_w_long", "fclib_global/H", source=GLOBAL)
def _(f):
    m = f["fclib_global/vectors/w"].shape[0]
    replace(f, "fclib_global/vectors/w", np.ones(m + 3))
    replace(f, "fclib_global/vectors/mu", np.full((m + 3) // 3, 0.3))


@case("global_G_without_b", "fclib_global/vectors/b", source=GLOBAL)
def _(f):
    n = f["fclib_global/vectors/f"].shape[0]
    g = f.create_group("fclib_global/G")
    for key, value in dict(m=n, n=1, nz=-1, nzmax=1).items():
        g[key] = np.array([value], np.int32)
    g["p"], g["i"], g["x"] = np.array([0, 1], np.int32), np.array([0], np.int32), np.ones(1)


@case("global_singular_M", "fclib_global/M", commands="solve", source=GLOBAL)
def _(f):
    n = f["fclib_global/vectors/f"].shape[0]
    x = np.ones(n)
    x[0] = 0.0  # an explicit zero on the diagonal: M is structurally fine, singular
    csc(f, "fclib_global/M", n, n, np.arange(n + 1), np.arange(n), x)


@case("guess_of_wrong_size", "guesses/1/r", commands="warm")
def _(f):
    if "guesses" in f:
        del f["guesses"]
    g = f.create_group("guesses")
    g["number_of_guesses"] = np.array([1], np.int32)
    g.create_group("1")["r"] = np.ones(5)


@case("guess_count_without_groups", "guesses/2", commands="warm")
def _(f):
    if "guesses" in f:
        del f["guesses"]
    g = f.create_group("guesses")
    g["number_of_guesses"] = np.array([INT_MAX], np.int32)
    g.create_group("1")["r"] = np.zeros(12)


def write_truncated(name, source, fraction):
    data = (DATA / source).read_bytes()
    (OUT / f"{name}.hdf5").write_bytes(data[: int(len(data) * fraction)])


def main():
    if OUT.exists():
        shutil.rmtree(OUT)
    OUT.mkdir(parents=True)
    manifest = {}
    for name, c in sorted(CASES.items()):
        path = OUT / f"{name}.hdf5"
        shutil.copyfile(DATA / c["source"], path)
        with h5py.File(path, "r+") as f:
            c["edit"](f)
        manifest[path.name] = dict(dataset=c["dataset"], commands=c["commands"])
    # files that are not (or no longer) HDF5
    for name, fraction in [("truncated_half", 0.5), ("truncated_tail", 0.97)]:
        write_truncated(name, LOCAL, fraction)
        manifest[f"{name}.hdf5"] = dict(dataset="", commands="read")
    (OUT / "not_hdf5.hdf5").write_bytes(b"this is not an HDF5 file\n")
    manifest["not_hdf5.hdf5"] = dict(dataset="", commands="read")
    (OUT / "empty_file.hdf5").write_bytes(b"")
    manifest["empty_file.hdf5"] = dict(dataset="", commands="read")
    with h5py.File(OUT / "neither_group.hdf5", "w") as f:
        f["hello"] = np.ones(3)
    manifest["neither_group.hdf5"] = dict(dataset="", commands="read")
    for name in LIBHDF5:
        shutil.copyfile(REGRESSIONS / name, OUT / name)
        manifest[name] = dict(dataset="", commands="libhdf5")
    (OUT / "MANIFEST.json").write_text(json.dumps(manifest, indent=1, sort_keys=True) + "\n")
    print(f"{len(manifest)} files in {OUT}")


if __name__ == "__main__":
    main()
