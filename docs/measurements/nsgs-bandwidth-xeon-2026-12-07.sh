#!/usr/bin/env bash
# The single-threaded NSGS sweep against the memory-bandwidth bound, on the
# machine this runs on: seconds a sweep of `nsgs` (the sweep alone: the full
# error only after the last sweep, freezing off) in the natural order and
# coloured on 1 and 2 threads, then bench_bandwidth's copy and read rates, in
# turn, ROUNDS rounds. The bound is W's stored 3x3 blocks with their column
# indices (80 bytes a block) over the single-thread copy rate of the same
# round; blocks are counted from fcref's W.
# usage: B=build/fcsolve BW=build/bench/bench_bandwidth ROUNDS=5 \
#        bash nsgs-bandwidth-xeon-2026-12-07.sh PILE.hdf5 SWEEPS
f=$1; sweeps=$2
B=${B:-build/fcsolve}; BW=${BW:-build/bench/bench_bandwidth}
export OPENBLAS_NUM_THREADS=1
here=$(cd "$(dirname "$0")/../.." && pwd)
uptime
/usr/bin/python3 - "$f" "$here" <<'PY'
import sys
sys.path.insert(0, sys.argv[2] + '/../shared/tools')
import fcref, numpy as np, scipy.sparse as sp
W = sp.coo_matrix(fcref.load(sys.argv[1])['W'])
blocks = len(np.unique((W.row // 3).astype(np.int64) * (W.shape[1] // 3 + 1) + W.col // 3))
print('blocks', blocks, 'bytes a sweep', 80 * blocks)
PY
grep -m1 'model name' /proc/cpuinfo
for round in $(seq 1 ${ROUNDS:-5}); do
  for cfg in "natural:" "coloured-1t:--ordering coloured --threads 1" "coloured-2t:--ordering coloured --threads 2"; do
    name=${cfg%%:*}; opts=${cfg#*:}
    $B solve $f --solver nsgs --tol 1e-30 --max-iter $sweeps --freezing 0 --error_every 100000 --json $opts 2>&1 |
      /usr/bin/python3 -c "
import json,sys; d=json.load(sys.stdin)
print('$round $name sweeps', d['iterations'], 'solve %.3f ms/sweep %.4f err %.6e' % (d['solve_seconds'], 1e3*d['solve_seconds']/d['iterations'], d['error']))"
  done
  $BW --benchmark_repetitions=3 --benchmark_report_aggregates_only=true 2>/dev/null | grep -E "/1/real_time_median" | sed "s/^/$round /"
done
uptime
