#!/usr/bin/env bash
# Usage: scripts/callgrind_compare.sh build/fcsolve > out.tsv   (docs/results.md, "Consolidation")
# Instruction counts (callgrind "Collected") and iterations of whole `fcsolve solve`
# runs, three shared problems per family.
set -u
BIN=$1
D=${FCSOLVE_FCLIB:-$(cd "$(dirname "$0")/../.." && pwd)/shared/data/fclib}
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
LOCAL="local/Confeti-ex03-Fc3D-SBM.hdf5 local/OneObject-i100000-316.hdf5 local/NESpheres_10_1.hdf5"
GLOBAL="global/Box_Stacks-i0035-31-0.hdf5 global/LMGC_GlobalFrictionContactProblem00046.hdf5 global/GFC3D_Example1.hdf5"
run() {  # solver file
  local out ir it
  out=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null "$BIN" solve "$D/$2" --solver "$1" --json --max-time 60 2>/tmp/cg-$(basename "$BIN").err)
  ir=$(grep -o "Collected : [0-9]*" /tmp/cg-$(basename "$BIN").err | awk '{s+=$3} END {print s}')
  it=$(printf '%s' "$out" | python3 -c 'import json,sys; j=json.load(sys.stdin); print(j.get("iterations", j.get("info",{}).get("iterations","?")), j.get("status", j.get("info",{}).get("status","?")))' 2>/dev/null)
  printf '%s\t%s\t%s\t%s\n' "$1" "$(basename "$2")" "$ir" "$it"
}
SMALL="local/Confeti-ex03-Fc3D-SBM.hdf5 local/Rover4609.hdf5 local/NESpheres_10_1.hdf5"
for s in nsgs nsn-ac nsn-ac-hybrid ppa nipm aclm-newton; do for f in $LOCAL; do run $s $f; done; done
for f in $SMALL; do run vi-fp $f; done
for s in nsn-ac-global nipm aclm-newton ipm-socqp auto; do for f in $GLOBAL; do run $s $f; done; done
