"""The report's charts (matplotlib, Agg backend), each written as a PNG."""
import math
import zlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

from . import analysis  # noqa: E402
from .problems import problem_family  # noqa: E402
from .results import FAILURE_CLASSES  # noqa: E402

FAILURE_COLOURS = {
    "converged": "#2ca02c", "max-iterations": "#ff7f0e", "stalled": "#dbc234",
    "diverged": "#d62728", "nan": "#9467bd", "inaccurate": "#f7a1d5", "timeout": "#8c8c8c",
    "crash": "#222222",
}
NOT_RUN = "#ffffff"
DPI = 110


def solver_styles(solvers):
    """One colour per solver; peers (PEER:NAME) dashed with hollow markers."""
    cmap = plt.get_cmap("tab10" if len(solvers) <= 10 else "tab20")
    markers = "osD^v<>ph*X"
    return {s: dict(color=cmap(k % cmap.N), marker=markers[k % len(markers)],
                    linestyle="--" if ":" in s else "-", peer=":" in s)
            for k, s in enumerate(solvers)}


# The family view's colours: one per solver family, the same in every chart
# and every campaign; auto in bold black. Families not listed get a colour
# from FAMILY_SPARE_COLOURS chosen by a hash of the name (stable across runs).
FAMILY_COLOURS = {
    "nsgs": "#1f77b4", "newton": "#d62728", "ipm": "#9467bd", "vi": "#2ca02c",
    "ppa": "#8c564b", "admm": "#e377c2", "fixed-point": "#bcbd22", "siconos": "#ff7f0e",
    "auto": "#000000",
}
FAMILY_SPARE_COLOURS = ["#17becf", "#7f7f7f", "#aec7e8", "#98df8a", "#c5b0d5", "#c49c94"]
FAMILY_MARKERS = {"nsgs": "o", "newton": "s", "ipm": "D", "vi": "^", "ppa": "v",
                  "admm": "<", "fixed-point": ">", "siconos": "X", "auto": "*"}


def family_colour(family):
    if family in FAMILY_COLOURS:
        return FAMILY_COLOURS[family]
    return FAMILY_SPARE_COLOURS[zlib.crc32(family.encode()) % len(FAMILY_SPARE_COLOURS)]


def family_styles(lines, peers=()):
    """Styles of the family view's lines [(family, solver)], keyed by solver:
    the family's fixed colour, auto bold, peers (PEER:NAME or a family in
    `peers`) dashed."""
    styles = {}
    for family, solver in lines:
        peer = ":" in solver or family in peers
        styles[solver] = dict(color=family_colour(family), marker=FAMILY_MARKERS.get(family, "p"),
                              linestyle="--" if peer else "-", peer=peer,
                              linewidth=3.2 if family == "auto" else 1.6,
                              zorder=5 if family == "auto" else 2,
                              # a peer's name says its family (siconos:nsn-ac)
                              label=solver if family == solver or ":" in solver
                              else f"{family}: {solver}")
    return styles


def _save(fig, path):
    fig.savefig(path, dpi=DPI, bbox_inches="tight")
    plt.close(fig)
    return path


def _profile_panel(ax, rows, tol, measure, styles, solvers=None):
    """One Dolan-More profile (measure at tol) on ax; returns the problem count."""
    problems, solvers, T = analysis.measure_table(rows, measure, tol, solvers)
    tau = analysis.performance_ratios(T)
    taus = analysis.profile_axis(tau)
    rho = analysis.profile(tau, taus)
    for k, s in enumerate(solvers):
        st = styles[s]
        ax.step(taus, rho[k], where="post", color=st["color"], linestyle=st["linestyle"],
                linewidth=st.get("linewidth", 1.8), zorder=st.get("zorder", 2),
                label=f"{st.get('label', s)} ({rho[k, -1]:.0%})")
    ax.set_xscale("log", base=2)
    ax.set_xlim(1, taus[-1])
    ax.set_ylim(-0.02, 1.02)
    ax.grid(True, which="both", alpha=0.3)
    return len(problems)


def performance_profiles(rows, tol, path, styles):
    """Dolan-More profiles on time and on iterations at one tolerance."""
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    for ax, measure, label in zip(axes, ("seconds", "iterations"), ("time", "iterations")):
        n = _profile_panel(ax, rows, tol, measure, styles)
        ax.set_xlabel(f"τ: {label} / best {label} on the problem")
        ax.set_title(f"performance profile on {label}, tol {tol:g} ({n} problems)", fontsize=10)
    axes[0].set_ylabel("ρ(τ): fraction of problems solved within τ of the best")
    axes[1].legend(loc="center left", bbox_to_anchor=(1.02, 0.5), fontsize=8,
                   title="solver (solved)", title_fontsize=8)
    return _save(fig, path)


def family_profiles(rows, tols, path, styles, solvers, note=""):
    """The family view's profiles on time, one panel per tolerance in tols,
    over the lines `solvers` only (ratios to the best of those lines)."""
    fig, axes = plt.subplots(1, len(tols), figsize=(5.2 * len(tols) + 2.2, 4.0), sharey=True,
                             squeeze=False)
    for ax, tol in zip(axes[0], tols):
        n = _profile_panel(ax, rows, tol, "seconds", styles, solvers)
        ax.set_xlabel("τ: time / best time of these lines on the problem")
        ax.set_title(f"time, tol {tol:g} ({n} problems)", fontsize=10)
    # one legend per panel: the solved fractions differ between tolerances
    for k, ax in enumerate(axes[0]):
        last = k == len(tols) - 1
        ax.legend(loc="center left" if last else "lower right",
                  bbox_to_anchor=(1.02, 0.5) if last else None, fontsize=7,
                  title="line (solved)", title_fontsize=7)
    axes[0][0].set_ylabel("ρ(τ): fraction solved within τ of the best")
    fig.suptitle("performance profiles: auto against each family's best member" + note,
                 fontsize=10)
    return _save(fig, path)


def work_precision(rows, path, styles, solvers=None, note=""):
    """Time to reach each accuracy and the fraction solved, against the
    tolerance, per solver (analysis.work_precision; `solvers`: those lines only)."""
    wp = analysis.work_precision(rows, solvers)
    fig, (ax_t, ax_f) = plt.subplots(1, 2, figsize=(11, 4.2))
    for s, points in wp.items():
        st = styles[s]
        tols = [p[0] for p in points]
        times = [p[1] if p[1] is not None else np.nan for p in points]
        kw = dict(color=st["color"], linestyle=st["linestyle"], marker=st["marker"],
                  linewidth=st.get("linewidth", 1.5), zorder=st.get("zorder", 2),
                  label=st.get("label", s))
        ax_t.plot(tols, times, **kw)
        ax_f.plot(tols, [p[2] for p in points], **kw)
    for ax in (ax_t, ax_f):
        ax.set_xscale("log")
        ax.invert_xaxis()  # tighter tolerance to the right
        ax.set_xlabel("tolerance on the recomputed error")
        ax.grid(True, which="both", alpha=0.3)
    ax_t.set_yscale("log")
    ax_t.set_ylabel("geometric-mean time [s] (unsolved: time limit)")
    ax_t.set_title("work-precision: time to reach the accuracy" + note, fontsize=10)
    ax_f.set_ylim(-0.02, 1.02)
    ax_f.set_ylabel("fraction of problems solved")
    ax_f.set_title("robustness: solved fraction per accuracy", fontsize=10)
    ax_f.legend(loc="lower left", fontsize=8)
    return _save(fig, path)


def time_vs_error(rows, path, styles):
    """Every run: achieved (recomputed) error against time; hollow = not solved."""
    fig, ax = plt.subplots(figsize=(11, 5))
    floor = 1e-17
    for s in analysis.solver_names(rows):
        st = styles[s]
        rs = [r for r in rows if r["solver"] == s and r["error"] is not None
              and math.isfinite(r["error"]) and r["seconds"] is not None]
        for solved, face in ((True, st["color"]), (False, "none")):
            pts = [r for r in rs if r["solved"] == solved]
            if pts:
                ax.scatter([max(r["error"], floor) for r in pts],
                           [max(r["seconds"], analysis.MEASURE_FLOOR["seconds"]) for r in pts],
                           s=22, marker=st["marker"], facecolors=face, edgecolors=st["color"],
                           linewidths=1.0, alpha=0.85, label=s if solved or not any(
                               r["solved"] for r in rs) else None)
    for tol in analysis.tolerances(rows):
        ax.axvline(tol, color="0.6", linestyle=":", linewidth=1)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("achieved error (recomputed from the returned solution)")
    ax.set_ylabel("time [s]")
    ax.set_title("speed against accuracy, every run (hollow: error above its tolerance; "
                 "dotted: tolerances)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize=8)
    return _save(fig, path)


def failure_map(rows, tol, path, solvers=None, labels=None, note=""):
    """Problems (grouped by family) x solvers, coloured by failure class
    (`solvers`: those columns only, named by `labels` {solver: text})."""
    at = [r for r in rows if r["tol"] == tol]
    solvers = analysis.solver_names(at) if solvers is None else list(solvers)
    family = {r["problem"]: r.get("family") or problem_family(r["problem"]) for r in at}
    problems = sorted(family, key=lambda p: (family[p].lower(), p))
    classes = FAILURE_CLASSES + ["not run"]
    index = {c: k for k, c in enumerate(classes)}
    grid = np.full((len(problems), len(solvers)), index["not run"])
    pi = {p: k for k, p in enumerate(problems)}
    si = {s: k for k, s in enumerate(solvers)}
    for r in (r for r in at if r["solver"] in si):
        grid[pi[r["problem"]], si[r["solver"]]] = index.get(r["failure"], index["crash"])
    height = min(2.2 + 0.19 * len(problems), 40)
    fig, ax = plt.subplots(figsize=(max(6.5, 2.6 + 0.55 * len(solvers)), height))
    cmap = ListedColormap([FAILURE_COLOURS.get(c, NOT_RUN) for c in classes])
    ax.imshow(grid, cmap=cmap, vmin=-0.5, vmax=len(classes) - 0.5, aspect="auto",
              interpolation="nearest")
    ax.set_xticks(range(len(solvers)))
    ax.set_xticklabels([(labels or {}).get(s, s) for s in solvers], rotation=45, ha="right",
                       fontsize=8)
    if len(problems) <= 150:
        ax.set_yticks(range(len(problems)))
        ax.set_yticklabels(problems, fontsize=7)
    else:
        ax.set_yticks([])
    # family bands: separators, and the family name on the right
    start = 0
    for k in range(1, len(problems) + 1):
        if k == len(problems) or family[problems[k]] != family[problems[start]]:
            if k < len(problems):
                ax.axhline(k - 0.5, color="black", linewidth=1.2)
            ax.text(len(solvers) - 0.4, (start + k - 1) / 2, family[problems[start]],
                    va="center", ha="left", fontsize=8, fontweight="bold")
            start = k
    ax.set_xticks(np.arange(-0.5, len(solvers)), minor=True)
    ax.grid(which="minor", axis="x", color="white", linewidth=1.5)
    ax.tick_params(which="minor", length=0)
    present = [c for c in classes if c in {classes[v] for v in np.unique(grid)}]
    ncol = min(len(present), 5)
    ax.legend(handles=[Patch(facecolor=FAILURE_COLOURS.get(c, NOT_RUN), edgecolor="0.5", label=c)
                       for c in present], loc="lower left", bbox_to_anchor=(0, 1.0),
              ncol=ncol, fontsize=8, frameon=False)
    rows_of_legend = -(-len(present) // ncol)
    ax.set_title(f"where methods fail, tol {tol:g}: problems by family x solvers{note}", fontsize=10,
                 pad=8 + 17 * rows_of_legend)
    return _save(fig, path)
