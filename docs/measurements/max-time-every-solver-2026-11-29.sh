#!/bin/bash
# Issue 13's max-time target, checked for every solver of the catalogue:
# `fcsolve solve FILE --solver S --tol 1e-8 --max-time T --json` in its own
# process, for each S of `fcsolve solvers` and each FILE; prints the
# process' wall time, the solver's own seconds (set-up included), its
# set-up, iterations and seconds per iteration, and OVER where the own time
# exceeds T + 10 % + one iteration + 0.05 s. FC/I-only solvers given an
# FC/II file answer with a usage error (exit 2, "no json").
#   bash docs/measurements/max-time-every-solver-2026-11-29.sh FCSOLVE T FILE...
set -u
B=$1 T=$2
shift 2
S=$("$B" solvers --json | python3 -c "import sys, json; print(' '.join(x['name'] for x in json.load(sys.stdin)))")
for f in "$@"; do
  for s in $S; do
    t0=$(date +%s.%N)
    out=$(timeout 300 "$B" solve "$f" --solver "$s" --tol 1e-8 --max-time "$T" --json 2>&1); rc=$?
    wall=$(python3 -c "print('%.2f' % ($(date +%s.%N) - $t0))")
    echo "$out" | python3 -c "
import json, sys
name, solver, rc, wall, limit = sys.argv[1:6]
try:
    d = json.loads(sys.stdin.read())
except ValueError:
    print('%-30s %-15s rc=%s wall=%s no json' % (name, solver, rc, wall))
    sys.exit()
per = d.get('solve_seconds', 0) / max(d['iterations'], 1)
over = 'OVER' if d['seconds'] > 1.1 * float(limit) + per + 0.05 else ''
print('%-30s %-15s rc=%s wall=%s own=%.2f setup=%.2f it=%d per_it=%.3f %s %.1e %s' % (
    name, solver, rc, wall, d['seconds'], d.get('setup_seconds', 0), d['iterations'], per,
    d['status'], d['error'], over))" "$(basename "$f")" "$s" "$rc" "$wall" "$T"
  done
done
