#!/usr/bin/env bash
# The scaling study (issue 13, item 4): how time, iterations and peak memory
# grow with the number of contacts, for sphere piles and elastic blocks.
#   bash scripts/scaling.sh [OUT_DIR]        (default /tmp/fcsolve-scaling)
# Environment:
#   SIZES        target contact counts          (default "100 1000 10000 100000")
#   FEM_SIZES    the same for fem-block         (default "100 1000 10000")
#   TIME_LIMIT   --max-time of every run, s     (default 60)
#   SOLVERS      comma-separated catalogue names
#                (default nsgs,nsn-ac,nsn-ac-global,nipm,aclm-newton,auto)
# Writes OUT_DIR/*.hdf5 (FC/I, outside the repository), OUT_DIR/MANIFEST.csv,
# OUT_DIR/scaling.csv (scripts/scaling_run.py: one row per solver, problem and
# tolerance 1e-4, 1e-6, 1e-8) and OUT_DIR/scaling.png + the log-log slopes
# (scripts/scaling_chart.py, Debian's python3 for matplotlib; docs/results.md
# quotes them).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
OUT="${1:-/tmp/fcsolve-scaling}"
case "$(realpath -m "$OUT")/" in
  "$ROOT"/*) echo "scaling.sh: $OUT is inside the repository; write elsewhere" >&2; exit 2 ;;
esac
SIZES="${SIZES:-100 1000 10000 100000}"
FEM_SIZES="${FEM_SIZES:-100 1000 10000}"
TIME_LIMIT="${TIME_LIMIT:-60}"
SOLVERS="${SOLVERS:-nsgs,nsn-ac,nsn-ac-global,nipm,aclm-newton,auto}"
CLI="${FCSOLVE_CLI:-$ROOT/build/fcsolve}"
[[ -x "$CLI" ]] || bash "$ROOT/scripts/build.sh" --target fcsolve_cli
mkdir -p "$OUT"
export OPENBLAS_NUM_THREADS=1

manifest="$OUT/MANIFEST.csv"
echo "file,scene,nc,n,generate_seconds" > "$manifest"
generate() {  # scene target; a file generated before (with its .gen line) is kept
  local file="$1-$2.hdf5" start=$SECONDS line
  # Elastic trajectories: 3 steps (their GlobalNewton factorises a fill-heavy LU).
  local steps=()
  [[ "$1" == fem-* ]] && steps=(--steps 3)
  if [[ -f "$OUT/$file" && -f "$OUT/$file.gen" ]]; then
    line=$(cat "$OUT/$file.gen")
  else
    line=$("$CLI" generate "$1" --contacts "$2" --seed 1 --mu 0.5 "${steps[@]}" --out "$OUT/$file")
    echo "$line" > "$OUT/$file.gen"
  fi
  local nc n
  nc=$(sed -n 's/.* nc=\([0-9]*\).*/\1/p' <<<"$line")
  n=$(sed -n 's/.* n=\([0-9]*\).*/\1/p' <<<"$line")
  local seconds
  seconds=$(sed -n 's/.* seconds=\([0-9.]*\).*/\1/p' <<<"$line")
  echo "$file,$1,$nc,$n,${seconds:-$((SECONDS - start))}" >> "$manifest"
  echo "$file: nc=$nc n=$n, generated in ${seconds:-$((SECONDS - start))} s"
}
for nc in $SIZES; do generate sphere-pile "$nc"; done
for nc in $FEM_SIZES; do generate fem-block "$nc"; done

python3 "$ROOT/scripts/scaling_run.py" "$OUT" --cli "$CLI" --solvers "$SOLVERS" \
  --time-limit "$TIME_LIMIT"
/usr/bin/python3 "$ROOT/scripts/scaling_chart.py" "$OUT/scaling.csv" --out "$OUT/scaling.png"
