#!/usr/bin/env bash
# solve-only seconds of nsgs (natural / coloured 1t / coloured 2t), alternating rounds
cli=/work/ci-run12/build/fcsolve
f=$1; sweeps=$2
for round in 1 2 3; do
  for cfg in "natural:" "coloured-1t:--ordering coloured --threads 1" "coloured-2t:--ordering coloured --threads 2"; do
    name=${cfg%%:*}; opts=${cfg#*:}
    $cli solve $f --solver nsgs --tol 1e-30 --max-iter $sweeps --freezing 0 --json $opts 2>&1 | /usr/bin/python3 -c "
import json,sys; d=json.load(sys.stdin)
print('$round $name sweeps', d['iterations'], 'setup %.3f solve %.3f ms/sweep %.3f err %.6e' % (d['setup_seconds'], d['solve_seconds'], 1e3*d['solve_seconds']/d['iterations'], d['error']))"
  done
done
