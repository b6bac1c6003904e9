#!/usr/bin/env python3
"""Chart and log-log slopes of a scaling study (scripts/scaling_run.py's CSV).

The chart: one row of panels per scene, one column per tolerance, wall time
against the number of contacts on log-log axes, one line per solver; a
point is drawn only where the solver reached that tolerance. The slopes,
printed as a Markdown table: least-squares slope of log(time) against
log(nc) over the sizes a solver solved, for the solver's own time (setup,
reduction included, and solve; not the process start) to reach the tolerance
and for the time per iteration (setup excluded), the figure to hold against
the cost of one sweep or one factorisation.
"""
import argparse
import csv
import math
from collections import defaultdict

COLOURS = {"nsgs": "tab:blue", "nsn-ac": "tab:orange", "nsn-ac-global": "tab:red",
           "nipm": "tab:green", "aclm-newton": "tab:olive", "auto": "black"}


def slope(points):
    """Least-squares slope of log y on log x, None with fewer than 2 sizes."""
    pts = [(math.log(x), math.log(y)) for x, y in points if x > 0 and y > 0]
    if len({x for x, _ in pts}) < 2:
        return None
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    sxx = sum((x - mx) ** 2 for x, _ in pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sxx


def load(path):
    with open(path) as f:
        return [r for r in csv.DictReader(f)]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv")
    ap.add_argument("--out", help="PNG to write (needs matplotlib)")
    args = ap.parse_args()
    rows = [r for r in load(args.csv) if r["converged"] == "True"]
    scenes = sorted({r["scene"] for r in load(args.csv)})
    tols = sorted({float(r["tol"]) for r in load(args.csv)}, reverse=True)
    solvers = list(dict.fromkeys(r["solver"] for r in load(args.csv)))

    series = defaultdict(list)  # (scene, solver, tol) -> [(nc, wall, per-iteration)]
    for r in rows:
        iters = int(r["iterations"] or 0)
        per_iter = float(r["solve_seconds"]) / iters if iters > 0 else None
        # The solver's own time (setup, reduction included, + solve): the
        # process start and the file read would flatten the small sizes.
        own = float(r["setup_seconds"] or 0) + float(r["solve_seconds"] or 0)
        series[(r["scene"], r["solver"], float(r["tol"]))].append(
            (int(r["nc"]), max(own, 1e-6), per_iter))

    print("| scene | solver | " + " | ".join("slope t(%.0e)" % t for t in tols) +
          " | slope t/iteration | sizes solved at %.0e |" % tols[-1])
    print("|---|---|" + "---|" * len(tols) + "---|---|")
    for scene in scenes:
        for solver in solvers:
            cells = []
            for tol in tols:
                s = slope([(nc, t) for nc, t, _ in series[(scene, solver, tol)]])
                cells.append("-" if s is None else "%.2f" % s)
            mid = tols[len(tols) // 2]
            per = slope([(nc, p) for nc, _, p in series[(scene, solver, mid)] if p])
            sizes = sorted(nc for nc, _, _ in series[(scene, solver, tols[-1])])
            print("| %s | %s | %s | %s | %s |" % (scene, solver, " | ".join(cells),
                                                  "-" if per is None else "%.2f" % per,
                                                  ", ".join(map(str, sizes)) or "none"))

    if not args.out:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(len(scenes), len(tols), figsize=(4.2 * len(tols), 3.4 * len(scenes)),
                             squeeze=False, sharex="row")
    for i, scene in enumerate(scenes):
        for j, tol in enumerate(tols):
            ax = axes[i][j]
            for solver in solvers:
                pts = sorted(series[(scene, solver, tol)])
                if pts:
                    ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=solver,
                              color=COLOURS.get(solver))
            ax.set_title("%s, error <= %.0e" % (scene, tol), fontsize=10)
            ax.set_xlabel("contacts")
            if j == 0:
                ax.set_ylabel("solver time to reach tol (s)")
            ax.grid(True, which="both", alpha=0.3)
    handles, labels = [], []
    for ax in axes.flat:
        for h, l in zip(*ax.get_legend_handles_labels()):
            if l not in labels:
                handles.append(h)
                labels.append(l)
    fig.legend(handles, labels, loc="lower center", ncol=len(labels))
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    fig.savefig(args.out, dpi=110)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
