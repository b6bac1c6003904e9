#!/usr/bin/env bash
# solve-only seconds of nsgs (coloured 1 thread / 2 threads; NATURAL=1 adds the natural order): the CLI of main before the change (/tmp/fcsolve-s6, bec7b25) against the change (/tmp/fcsolve-par), alternating, ROUNDS rounds
# usage: ROUNDS=3 bash parallel-nsgs-chunked-2026-11-28.sh PILE.hdf5 SWEEPS
f=$1; sweeps=$2
export OPENBLAS_NUM_THREADS=1
for round in $(seq 1 ${ROUNDS:-3}); do
  for cli in /tmp/fcsolve-s6 /tmp/fcsolve-par; do
  for cfg in ${NATURAL:+"natural:"} "coloured-1t:--ordering coloured --threads 1" "coloured-2t:--ordering coloured --threads 2"; do
    name=${cfg%%:*}; opts=${cfg#*:}
    $cli solve $f --solver nsgs --tol 1e-30 --max-iter $sweeps --freezing 0 --json $opts 2>&1 | /usr/bin/python3 -c "
import json,sys; d=json.load(sys.stdin)
print('$round ${cli##*-} $name sweeps', d['iterations'], 'setup %.3f solve %.3f ms/sweep %.3f err %.6e' % (d['setup_seconds'], d['solve_seconds'], 1e3*d['solve_seconds']/d['iterations'], d['error']))"
  done
  done
done
