#!/usr/bin/env python3
"""Chart of the warm start's effect along trajectories, from the per-step CSV
files that warm_start_table.py --per-step writes (needs matplotlib).

    warm_start_chart.py --out docs/img/warm_start.png TITLE=FILE.csv [TITLE=FILE.csv ...]

One panel per file: iterations per step with and without the warm start
(log scale), and the cumulative solver time of both runs.
"""
import argparse
import csv

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True)
    ap.add_argument("runs", nargs="+", help="TITLE=FILE.csv")
    a = ap.parse_args()
    fig, axes = plt.subplots(2, len(a.runs), figsize=(5.5 * len(a.runs), 6.5), squeeze=False,
                             sharex="col")
    for j, run in enumerate(a.runs):
        title, path = run.split("=", 1)
        d = read(path)
        top, bottom = axes[0][j], axes[1][j]
        for key, label, style in (("cold", "no warm start", "-"), ("warm", "warm start", "-")):
            it = [max(x, 0.8) for x in d[f"iterations_{key}"]]
            top.plot(d["step"], it, style, lw=0.8, label=label, alpha=0.85)
            total, cum = 0.0, []
            for t in d[f"time_{key}"]:
                total += t
                cum.append(total)
            bottom.plot(d["step"], cum, style, lw=1.2, label=label)
        top.set_yscale("log")
        top.set_title(title, fontsize=10)
        top.set_ylabel("iterations per step")
        bottom.set_ylabel("cumulative solver time (s)")
        bottom.set_xlabel("step")
        top.legend(fontsize=8)
        bottom.legend(fontsize=8)
        for ax in (top, bottom):
            ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)


if __name__ == "__main__":
    main()
