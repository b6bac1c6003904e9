"""Problem files of a campaign: discovery, short names, families, sizes."""
import glob
import os
import re

import h5py
import numpy as np


def find_problem_files(paths):
    """FCLIB files named by `paths` (files, directories searched recursively, globs)."""
    found = []
    for p in paths:
        if os.path.isdir(p):
            for root, _, files in os.walk(p):
                found += [os.path.join(root, f) for f in files if f.endswith((".hdf5", ".h5"))]
        elif os.path.exists(p):
            found.append(p)
        else:
            matches = glob.glob(p)
            if not matches:
                raise FileNotFoundError(f"no problem file matches {p!r}")
            found += matches
    return sorted(dict.fromkeys(os.path.normpath(f) for f in found))


def problem_name(path):
    """The file name without its extension: the problem's key in the CSV."""
    base = os.path.basename(path)
    for ext in (".hdf5", ".h5"):
        if base.endswith(ext):
            return base[: -len(ext)]
    return base


def problem_names(paths):
    """Unique names: the stem, or parent/stem where two files share a stem."""
    stems = [problem_name(p) for p in paths]
    names = []
    for p, s in zip(paths, stems):
        if stems.count(s) > 1:
            s = f"{os.path.basename(os.path.dirname(os.path.abspath(p)))}/{s}"
        names.append(s)
    if len(set(names)) != len(names):
        raise ValueError("problem files with the same name in folders of the same name")
    return names


_FAMILY_CUT = re.compile(r"(?<=[a-z_])_?\d")
_SOURCE_PREFIXES = ("LMGC_",)  # LMGC90 dumps: LMGC_100_PR_PerioBox-..., LMGC_GlobalFriction...


def problem_family(name):
    """The problem set a file belongs to, from FCLIB's naming habits.

    FCLIB files are named SET-iSTEP-... (Capsules-i101-404, KaplasTower-i..),
    SETnnnn (Rover1039), SET_nn (NESpheres_10_1) or SET_Examplen: keep what
    comes before the first '-', then cut at the first number that follows a
    lower-case letter or '_' (CubeH8, Cubes_H8_2 keep the element name H8; a
    leading number, as in 945_SP_Box_PL, is kept). LMGC90 dumps
    (LMGC_100_PR_PerioBox, LMGC_GlobalFrictionContactProblem00046) are "LMGC".
    """
    stem = name.rsplit("/", 1)[-1].split("-", 1)[0]
    for prefix in _SOURCE_PREFIXES:
        if stem.startswith(prefix):
            return prefix.rstrip("_")
    m = _FAMILY_CUT.search(stem)
    family = stem[: m.start()] if m and m.start() > 0 else stem
    return family.rstrip("_") or stem


def problem_info(path):
    """kind, d, nc, n (global only, else None) and m of an FCLIB file, read cheaply."""
    def scalar(ds):
        return int(np.asarray(ds).ravel()[0])

    with h5py.File(path, "r") as f:
        if "fclib_local" in f:
            g, kind = f["fclib_local"], "local"
            n = None
        elif "fclib_global" in f:
            g, kind = f["fclib_global"], "global"
            n = scalar(g["M/n"])
        else:
            raise ValueError(f"{path}: neither /fclib_local nor /fclib_global")
        d = scalar(g["spacedim"])
        nc = int(g["vectors/mu"].shape[0])
    return dict(kind=kind, d=d, nc=nc, n=n, m=d * nc)
