#!/usr/bin/env python3
"""Time per sweep of the coloured (parallel) NSGS against the natural one.

For each FC/II file, `fcsolve solve FILE --solver nsgs` runs a fixed number
of sweeps (--tol 1e-30, no freezing, no full error but the last) in three
configurations: natural order, coloured with 1 thread, coloured with 2
threads (libgomp's default wait policy, then OMP_WAIT_POLICY=passive); each --repeat times, the fastest kept (the machine is shared).
Two clocks: wall time per sweep (the solve's own seconds / sweeps), and CPU
time per sweep (the process's user + sys time, less that of a 1-sweep run,
over the other sweeps): on a loaded machine the CPU time of a 1-thread run
is what the sweep costs while it runs, the wall time is what it costs there.
The bandwidth columns divide the bytes of W's stored d x d blocks and their
indices (BlockSparseStorage: 8 d^2 bytes a block, 8 for its column, 8 a
block row) by the 1-thread CPU time per sweep, against --bandwidth (GB/s,
bench_bandwidth's BM_Sum/1 on CPU time).

    /usr/bin/python3 bench/parallel_nsgs.py --bandwidth 25 /tmp/pnsgs/pile-1e4.hdf5
"""
import argparse
import os
import json
import resource
import subprocess
import sys
from pathlib import Path

import scipy.sparse as sp

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT.parent / "shared" / "tools"))
import fcref  # noqa: E402  (independent FCLIB reader)

COLOURED = ["--ordering", "coloured", "--threads"]
# (name, options, environment): libgomp's threads spin at a barrier before
# they sleep; OMP_WAIT_POLICY=passive sleeps at once (better when the cores
# are shared with other jobs).
CONFIGS = [("natural", [], {}),
           ("coloured, 1 thread", COLOURED + ["1"], {}),
           ("coloured, 2 threads", COLOURED + ["2"], {}),
           ("coloured, 2 threads, passive", COLOURED + ["2"], {"OMP_WAIT_POLICY": "passive"})]


def streamed_bytes(path):
    """Bytes of W's stored blocks and indices that one sweep reads."""
    p = fcref.load(path)
    d = p["d"]
    nblocks = sp.bsr_matrix(p["W"], blocksize=(d, d)).indices.size
    nc = p["W"].shape[0] // d
    return nblocks * (8 * d * d + 8) + 8 * (nc + 1), nc, nblocks


def run(cli, path, sweeps, extra, env):
    """(wall seconds of the sweeps, CPU seconds of the process, error). The
    wall time is the solve's own (solve_seconds): the setup, which holds the
    colouring and the reordering of W, would hide the sweeps' speed-up."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run([cli, "solve", path, "--solver", "nsgs", "--tol", "1e-30",
                          "--max-iter", str(sweeps), "--freezing", "0",
                          "--error_every", "1000000000", "--json", *extra],
                         capture_output=True, text=True, env=dict(os.environ, **env)).stdout  # exit 1: not converged
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    fields = json.loads(out)
    assert int(fields["iterations"]) == sweeps, out
    return float(fields["solve_seconds"]), cpu, f'{fields["error"]:.3e}'


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="+")
    ap.add_argument("--cli", default=str(ROOT / "build" / "fcsolve"))
    ap.add_argument("--sweeps", type=int, default=100)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--bandwidth", type=float, required=True, help="GB/s")
    args = ap.parse_args()
    print("| problem | nc | blocks | MB/sweep "
          "| ms/sweep wall: natural, coloured 1t, 2t, 2t passive "
          "| 2t speed-up (wall) over coloured 1t: default, passive "
          "| ms/sweep CPU: natural, coloured 1t | GB/s (of bw), CPU: natural, coloured 1t |")
    print("|---|---|---|---|---|---|---|---|")
    for path in args.files:
        nbytes, nc, nblocks = streamed_bytes(path)
        wall, cpu, errors = [], [], []
        for _, extra, env in CONFIGS:
            base = min(run(args.cli, path, 1, extra, env)[1] for _ in range(args.repeat))
            runs = [run(args.cli, path, args.sweeps, extra, env) for _ in range(args.repeat)]
            wall.append(min(r[0] for r in runs) / args.sweeps)
            cpu.append((min(r[1] for r in runs) - base) / (args.sweeps - 1))
            errors.append(runs[0][2])
        nat, c1, c2, c2p = wall
        rate = [nbytes / t / 1e9 for t in cpu[:2]]
        print(f"| {Path(path).name} | {nc} | {nblocks} | {nbytes / 1e6:.1f} "
              f"| {nat * 1e3:.2f}, {c1 * 1e3:.2f}, {c2 * 1e3:.2f}, {c2p * 1e3:.2f} "
              f"| {c1 / c2:.2f}x, {c1 / c2p:.2f}x "
              f"| {cpu[0] * 1e3:.2f}, {cpu[1] * 1e3:.2f} "
              f"| {rate[0]:.2f} ({rate[0] / args.bandwidth:.0%}), "
              f"{rate[1]:.2f} ({rate[1] / args.bandwidth:.0%}) |", flush=True)
        print(f"  errors after {args.sweeps} sweeps: " + ", ".join(
            f"{name} {e}" for (name, _, _), e in zip(CONFIGS, errors)), file=sys.stderr)


if __name__ == "__main__":
    main()
