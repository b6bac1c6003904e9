#!/usr/bin/env bash
# The NSGS sweep before (OLD: the CLI of main 8496395) and after (NEW) the
# off-diagonal row product's two loops: solve-only seconds per sweep of nsgs
# in the natural order and coloured on 1 and 2 threads, alternating, ROUNDS
# rounds; then the hot loop of bench_nsgs nsgs-small (OLD_BENCH / NEW_BENCH)
# and bench_bandwidth, on the same quiet minutes.
# EXTRA: more solve options for every run (e.g. --error_every 100000: the
# sweep alone, the full error only after the last sweep).
# usage: OLD=... NEW=... OLD_BENCH=... NEW_BENCH=... BANDWIDTH=... \
#        ROUNDS=3 [EXTRA=...] bash nsgs-row-split-2026-11-28.sh PILE.hdf5 SWEEPS
f=$1; sweeps=$2
export OPENBLAS_NUM_THREADS=1
uptime
for round in $(seq 1 ${ROUNDS:-3}); do
  for cli in "$OLD" "$NEW"; do
    tag=$([ "$cli" = "$OLD" ] && echo old || echo new)
    for cfg in "natural:" "coloured-1t:--ordering coloured --threads 1" "coloured-2t:--ordering coloured --threads 2"; do
      name=${cfg%%:*}; opts=${cfg#*:}
      $cli solve $f --solver nsgs --tol 1e-30 --max-iter $sweeps --freezing 0 --json $opts $EXTRA 2>&1 | /usr/bin/python3 -c "
import json,sys; d=json.load(sys.stdin)
print('$round $tag $name sweeps', d['iterations'], 'setup %.3f solve %.3f ms/sweep %.4f err %.6e' % (d['setup_seconds'], d['solve_seconds'], 1e3*d['solve_seconds']/d['iterations'], d['error']))"
    done
  done
done
if [ -n "$OLD_BENCH" ]; then
  for round in $(seq 1 ${ROUNDS:-3}); do
    for b in "$OLD_BENCH" "$NEW_BENCH"; do
      tag=$([ "$b" = "$OLD_BENCH" ] && echo old || echo new)
      $b --benchmark_filter='nsgs-small' --benchmark_repetitions=5 --benchmark_report_aggregates_only=true 2>/dev/null |
        awk -v r=$round -v t=$tag '/_median/ {print r, t, $1, $2, $3}'
    done
  done
fi
[ -n "$BANDWIDTH" ] && $BANDWIDTH --benchmark_repetitions=3 --benchmark_report_aggregates_only=true 2>/dev/null | grep -E "_median"
uptime
