#!/usr/bin/env python3
"""What the warm start saves over a trajectory: runs a time-stepping example
with and without --no-warm-start and prints one Markdown table row.

    warm_start_table.py [--repeat 3] [--per-step FILE.csv] -- EXAMPLE [ARGS...]

Iterations are deterministic; times are the solver's (compute + solve) summed
over the steps, the smallest of --repeat runs (the machine may be shared).
--per-step writes step, contacts, iterations and time of both runs as CSV.
"""
import argparse
import os
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_stepping import parse_table  # noqa: E402


def trajectory(cmd, repeat):
    best = None
    for _ in range(repeat):
        out = subprocess.run(cmd, stdout=subprocess.PIPE, text=True).stdout
        header, rows, summary = parse_table(out)
        if best is None or float(summary["time_s"]) < float(best[2]["time_s"]):
            best = (header, rows, summary)
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--per-step")
    ap.add_argument("command", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    cmd = a.command[1:] if a.command[:1] == ["--"] else a.command
    _, warm, ws = trajectory(cmd, a.repeat)
    _, cold, cs = trajectory(cmd + ["--no-warm-start"], a.repeat)
    solved = [r for r in warm if r["contacts"] > 0]
    solved_cold = [r for r in cold if r["contacts"] > 0]
    it_w, it_c = int(ws["iterations"]), int(cs["iterations"])
    t_w, t_c = float(ws["time_s"]), float(cs["time_s"])
    failed_w = sum(1 for r in warm if r["status"] not in ("converged", "no-contact"))
    failed_c = sum(1 for r in cold if r["status"] not in ("converged", "no-contact"))
    med_w = statistics.median(r["iterations"] for r in solved) if solved else 0
    med_c = statistics.median(r["iterations"] for r in solved_cold) if solved_cold else 0
    mean_nc = statistics.mean(r["contacts"] for r in solved) if solved else 0
    print("| command | steps with contacts (mean nc) | iterations warm / cold | median per step | "
          "solver time warm / cold (s) | steps not converged warm / cold |")
    print("|---|---|---|---|---|---|")
    print(f"| `{os.path.basename(cmd[0])} {' '.join(cmd[1:])}` | {len(solved)} ({mean_nc:.0f}) | "
          f"{it_w} / {it_c} ({it_w / it_c:.2f}x) | {med_w:g} / {med_c:g} | "
          f"{t_w:.3g} / {t_c:.3g} ({t_w / t_c:.2f}x) | {failed_w} / {failed_c} |")
    if a.per_step:
        with open(a.per_step, "w") as f:
            f.write("step,contacts_warm,iterations_warm,time_warm,contacts_cold,iterations_cold,time_cold\n")
            for w, c in zip(warm, cold):
                f.write(f"{w['step']},{w['contacts']},{w['iterations']},{w['time']},"
                        f"{c['contacts']},{c['iterations']},{c['time']}\n")


if __name__ == "__main__":
    sys.exit(main())
