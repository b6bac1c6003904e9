#!/usr/bin/env python3
"""Issue 14's targets for `auto`, from one campaign CSV (`fcsolve bench`).

Per part of the problem set (the shared FCLIB files; the generated corpus'
train and holdout files, from its MANIFEST.csv) and per tolerance:

  T1  `auto` solves every problem that some other solver of the campaign
      solves; its total time is at most 1.3 x the virtual best (VB: per
      problem, the fastest other solver that solves it; summed over the
      problems some other solver solves); on no problem more than 3 x that
      problem's VB.
  T2  at the tightest tolerance, `auto` solves strictly more corpus problems
      than the best single solver.

Every other solver of the campaign counts, peers (siconos:NAME) included,
unless --fcsolve-only.

Solved and time are the campaign's: the recomputed FCLIB error <= tol, and
the solver's own setup + solve seconds (`seconds`, floored at 1 us as in
the report; --floor 0 compares the times as measured, which matters on
problems of one contact, solved in half a microsecond). A problem `auto`
misses counts at the run's time limit in the total (so a miss can only
make the ratio worse); the ratio on the problems both solve is printed
beside it.

    /usr/bin/python3 bench/auto_targets.py DIR/results.csv \\
        --manifest /tmp/fcsolve-corpus/MANIFEST.csv
"""
import argparse
import csv
import os
import sys
from pathlib import Path

# The campaign without the compiled extension (as `fcsolve bench` imports it).
_CAMPAIGN = Path(__file__).resolve().parents[1] / "python" / "fcsolve" / "campaign"
sys.path.insert(0, str(_CAMPAIGN))
import bootstrap  # noqa: E402

bootstrap.import_campaign(str(_CAMPAIGN))
sys.path.pop(0)
from fcsolve.campaign.analysis import MEASURE_FLOOR  # noqa: E402
from fcsolve.campaign.results import load_results  # noqa: E402

AUTO = "auto"
TOTAL_BOUND, PROBLEM_BOUND = 1.3, 3.0


def corpus_parts(manifest):
    """{file name: "corpus-train" | "corpus-holdout"} from the corpus' MANIFEST.csv."""
    with open(manifest, newline="") as f:
        return {r["file"]: "corpus-holdout" if r["holdout"] == "1" else "corpus-train"
                for r in csv.DictReader(f)}


def part_of(row, parts):
    return parts.get(os.path.basename(row["file"] or ""), "shared")


FLOOR = MEASURE_FLOOR["seconds"]


def seconds(row):
    return max(row["seconds"] or 0.0, FLOOR)


def targets(rows, tol):
    """T1 numbers of `auto` on rows (one part) at tol."""
    at = [r for r in rows if r["tol"] == tol]
    problems = list(dict.fromkeys(r["problem"] for r in at))
    auto = {r["problem"]: r for r in at if r["solver"] == AUTO}
    vb = {}  # problem -> (seconds, solver)
    for r in at:
        if r["solver"] != AUTO and r["solved"]:
            t = seconds(r)
            if r["problem"] not in vb or t < vb[r["problem"]][0]:
                vb[r["problem"]] = (t, r["solver"])
    auto_solved = {p for p, r in auto.items() if r["solved"]}
    missed = sorted(set(vb) - auto_solved)
    only_auto = sorted(auto_solved - set(vb))
    total_vb = sum(t for t, _ in vb.values())
    total_auto = sum(seconds(auto[p]) if p in auto_solved else (auto[p]["time_limit"] or 0.0)
                     for p in vb)
    both = [p for p in vb if p in auto_solved]
    both_auto = sum(seconds(auto[p]) for p in both)
    both_vb = sum(vb[p][0] for p in both)
    ratios = sorted(((seconds(auto[p]) / vb[p][0], p) for p in both), reverse=True)
    return dict(problems=len(problems), solved_by_other=len(vb), auto_solved=len(auto_solved),
                missed=missed, only_auto=only_auto, total_auto=total_auto, total_vb=total_vb,
                total_ratio=total_auto / total_vb if total_vb else float("nan"),
                both_ratio=both_auto / both_vb if both_vb else float("nan"),
                ratios=ratios, vb=vb, auto=auto)


def best_single(rows, tol):
    """(solved, solver) of the non-auto solver that solves the most at tol."""
    counts = {}
    for r in rows:
        if r["tol"] == tol and r["solver"] != AUTO:
            counts[r["solver"]] = counts.get(r["solver"], 0) + int(r["solved"])
    if not counts:
        return 0, None
    name = max(sorted(counts), key=lambda s: counts[s])
    return counts[name], name


def fmt_ms(t):
    return f"{t * 1e3:.3g} ms" if t < 1 else f"{t:.3g} s"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("csv", help="the campaign's results.csv (or its folder)")
    ap.add_argument("--manifest", default="/tmp/fcsolve-corpus/MANIFEST.csv",
                    help="the corpus' MANIFEST.csv: which files are corpus, which holdout")
    ap.add_argument("--details", action="store_true", help="every problem above 3x, every miss")
    ap.add_argument("--fcsolve-only", action="store_true",
                    help="leave the peers' runs (PEER:NAME) out of the virtual best and the best single "
                         "solver (the issue's VB: the fastest fcsolve solver)")
    ap.add_argument("--floor", type=float, default=MEASURE_FLOOR["seconds"], metavar="SECONDS",
                    help="times below this count as this (default: the report's %(default)g s; 0: none)")
    a = ap.parse_args()
    global FLOOR
    FLOOR = a.floor
    rows = load_results(a.csv)
    if a.fcsolve_only:
        rows = [r for r in rows if ":" not in r["solver"]]
    parts = corpus_parts(a.manifest)
    by_part = {}
    for r in rows:
        by_part.setdefault(part_of(r, parts), []).append(r)
    by_part["corpus (both parts)"] = by_part.get("corpus-train", []) + by_part.get("corpus-holdout", [])
    tols = sorted({r["tol"] for r in rows}, reverse=True)

    print("| part | tol | problems | solved by another solver | auto solves | missed by auto "
          "| auto total | VB total | x VB (misses at the limit) | x VB (both solved) "
          "| worst ratio | problems > 3x |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    results = {}
    for part in ["shared", "corpus-train", "corpus-holdout", "corpus (both parts)"]:
        for tol in tols:
            t = targets(by_part.get(part, []), tol)
            results[(part, tol)] = t
            worst = (f"{t['ratios'][0][0]:.2f} ({t['ratios'][0][1]})" if t["ratios"] else "-")
            over = sum(1 for q, _ in t["ratios"] if q > PROBLEM_BOUND)
            print(f"| {part} | {tol:g} | {t['problems']} | {t['solved_by_other']} | {t['auto_solved']} "
                  f"| {len(t['missed'])} | {fmt_ms(t['total_auto'])} | {fmt_ms(t['total_vb'])} "
                  f"| {t['total_ratio']:.2f} | {t['both_ratio']:.2f} | {worst} | {over} |")

    tight = min(tols)
    print(f"\nT2 at tol {tight:g}: auto against the best single solver")
    for part in ["corpus-train", "corpus-holdout", "corpus (both parts)"]:
        rs = by_part.get(part, [])
        n_auto = sum(1 for r in rs if r["tol"] == tight and r["solver"] == AUTO and r["solved"])
        n_best, name = best_single(rs, tight)
        verdict = "met" if n_auto > n_best else "NOT met"
        print(f"  {part}: auto {n_auto}, best single {name} {n_best}: {verdict}")

    print()
    for (part, tol), t in results.items():
        ok = (not t["missed"] and t["total_ratio"] <= TOTAL_BOUND
              and all(q <= PROBLEM_BOUND for q, _ in t["ratios"]))
        print(f"T1 {part} tol {tol:g}: {'met' if ok else 'NOT met'}")
        if not (a.details or not ok):
            continue
        for p in t["missed"]:
            r = t["auto"].get(p)
            print(f"    missed {p}: {t['vb'][p][1]} solves it in {fmt_ms(t['vb'][p][0])}; auto "
                  f"{r['failure'] if r else 'not run'} at error {r['error'] if r else '-'}")
        for p in t["only_auto"]:
            print(f"    only auto solves {p} ({fmt_ms(seconds(t['auto'][p]))})")
        for q, p in t["ratios"]:
            if q > PROBLEM_BOUND:
                print(f"    {q:.2f}x {p}: auto {fmt_ms(seconds(t['auto'][p]))}, "
                      f"VB {t['vb'][p][1]} {fmt_ms(t['vb'][p][0])}")


if __name__ == "__main__":
    main()
