#!/bin/bash
# Held-out scenes: `fcsolve generate` with seeds and parameter sets never
# used for tuning (seeds 101-116 and 201-210; the corpus of scripts/corpus.sh
# uses seeds 1-60), each solved by `fcsolve solve` (auto, tol 1e-8,
# --max-time 20) as FC/II (-local) and FC/I, and the returned solution's
# error recomputed by ../shared/tools/fcref.py.
#   bash docs/measurements/heldout-scenes-2026-11-28.sh [FCSOLVE] [OUTDIR]
#   ROUND=2 bash ...: the second round (2026-11-29), seeds 401-420, other
#   parameter sets, never used for tuning either.
#   ROUND=3 bash ...: the third (2026-11-29, later), seeds 501-516, with the
#   mixed-shapes scene (spheres and boxes) that no solver was tuned on.
#   ROUND=4 bash ...: the fourth (2026-12-07), seeds 601-620, after the
#   changes of stops 57-60, as a check that they generalise.
#   ROUND=5 bash ...: the fifth (2026-12-07, stop 62), seeds 701-720, after
#   the sweeps got back the time of an interior point that did not pay;
#   more large piles (the kind that change touched), chosen before any run.
#   ROUND=6 bash ...: the sixth (2026-12-07, stop 63), seeds 801-820, after
#   the interior point's crawl guard moved to one decade; chosen before any
#   run, piles of 900 to 12 000 among them (the kind that change touched).
#   ROUND=7 bash ...: the seventh (2026-12-07, stop 64), seeds 1001-1020
#   (9xx are development seeds), after stop 63's crawl guard and FC/I pile
#   route; chosen before any run, FC/I piles among them.
# Columns: file, wall seconds (process), exit code, status, solver,
# iterations, error, seconds | fcref.
set -u
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
FCREF=${FCREF:-$ROOT/../shared/tools/fcref.py}  # beside the checkout, as in CI
B=${1:-$ROOT/build/fcsolve}
OUT=${2:-/tmp/fcsolve-heldout}
mkdir -p "$OUT"
# scene contacts mu mass-ratio penetration-correction seed
SPECS=(
  "sphere-pile 50 0.5 1 0 101" "sphere-pile 400 1.5 1 0.2 102" "box-stack 20 0.3 1 0 103"
  "box-stack 200 2.0 1 0.1 104" "wall 100 0.8 1 0 105" "wall 800 0.2 1 0.2 106" "tower 60 1.0 1 0 107"
  "tower 500 2.0 1 0 108" "heavy-on-light 16 0.5 10000 0 109" "heavy-on-light 120 0.9 1000 0.2 110"
  "fem-block 100 0.5 1 0 111" "fem-block 400 1.2 1 0 112" "fem-two-bodies 100 0.4 1 0 113"
  "fem-two-bodies 300 0.0 1 0 114" "sphere-pile 2000 0.0 1 0 115" "box-stack 8 0.1 100 0 116"
  "wall 200 0.2 1 0.2 201" "wall 800 0.2 1 0.05 202" "wall 3000 0.5 1 0 203" "tower 2000 2.0 1 0.2 204"
  "heavy-on-light 300 1.0 10000 0.1 205" "box-stack 1000 0.6 100 0 206" "box-stack 50 2.0 10000 0.2 207"
  "sphere-pile 5000 0.3 1 0.1 208" "fem-block 1000 0.3 1 0 209" "fem-two-bodies 1000 1.0 1 0 210")
if [[ "${ROUND:-1}" == 2 ]]; then
  SPECS=(
    "sphere-pile 120 0.8 1 0.1 401" "sphere-pile 1200 0.4 1 0 402" "sphere-pile 3000 1.0 1 0.05 403"
    "box-stack 30 1.2 1 0.1 404" "box-stack 600 0.5 1000 0 405" "wall 300 1.5 1 0 406" "wall 1500 0.6 1 0.1 407"
    "tower 150 0.4 1 0.1 408" "tower 1000 1.2 1 0 409" "heavy-on-light 40 0.7 5000 0 410"
    "heavy-on-light 600 0.3 10000 0.05 411" "fem-block 200 0.9 1 0 412" "fem-block 700 0.2 1 0 413"
    "fem-two-bodies 200 0.6 1 0 414" "fem-two-bodies 600 1.5 1 0 415" "sphere-pile 10 0.3 1 0 416"
    "box-stack 4 0.5 1 0 417" "wall 50 2.0 1 0.2 418" "tower 4000 0.8 1 0.05 419" "sphere-pile 600 0.0 1 0.1 420")
fi
if [[ "${ROUND:-1}" == 3 ]]; then
  SPECS=(
    "mixed-shapes 40 0.5 1 0 501" "mixed-shapes 400 1.0 1 0.1 502" "mixed-shapes 1500 0.3 100 0 503"
    "mixed-shapes 3000 0.7 1 0.05 504" "mixed-shapes 200 0.0 1 0 505" "mixed-shapes 800 2.0 1000 0 506"
    "sphere-pile 800 0.9 1 0.1 507" "box-stack 150 0.7 1 0 508" "wall 600 1.0 10 0 509" "tower 700 0.6 1 0 510"
    "heavy-on-light 200 0.4 10000 0.1 511" "fem-block 300 0.7 1 0 512" "fem-two-bodies 400 0.8 10 0 513"
    "sphere-pile 6 0.5 1 0 514" "box-stack 4 1.0 1 0 515" "mixed-shapes 10 0.5 1 0 516")
fi
if [[ "${ROUND:-1}" == 4 ]]; then
  SPECS=(
    "sphere-pile 250 0.6 1 0 601" "sphere-pile 2500 1.2 1 0.1 602" "sphere-pile 8000 0.5 1 0 603"
    "box-stack 12 0.9 1 0.05 604" "box-stack 400 0.4 10000 0 605" "wall 150 0.3 1 0.1 606"
    "wall 2000 1.8 1 0 607" "tower 90 0.5 1 0.2 608" "tower 1500 0.7 100 0 609"
    "heavy-on-light 60 1.5 10000 0 610" "heavy-on-light 900 0.6 100 0.1 611" "mixed-shapes 120 1.4 1 0.05 612"
    "mixed-shapes 2000 0.5 10 0 613" "fem-block 150 1.0 1 0 614" "fem-block 1400 0.5 1 0 615"
    "fem-two-bodies 150 0.3 1 0 616" "fem-two-bodies 1500 0.9 1 0 617" "sphere-pile 20 0.0 1 0 618"
    "box-stack 6 2.0 1000 0 619" "wall 400 0.0 1 0.1 620")
fi
if [[ "${ROUND:-1}" == 5 ]]; then
  SPECS=(
    "sphere-pile 6000 0.7 1 0 701" "sphere-pile 4000 0.4 1 0.05 702" "sphere-pile 1500 1.0 1 0 703"
    "sphere-pile 300 0.2 10 0 704" "box-stack 100 1.5 1 0 705" "box-stack 2000 0.3 1 0.1 706"
    "wall 1000 0.9 1 0 707" "wall 250 1.2 100 0.05 708" "tower 300 1.5 1 0 709" "tower 2500 0.3 1 0.1 710"
    "heavy-on-light 150 0.8 10000 0 711" "heavy-on-light 1500 0.4 1000 0.05 712" "mixed-shapes 600 0.9 1 0 713"
    "mixed-shapes 5000 0.5 1 0.05 714" "fem-block 600 0.8 1 0 715" "fem-two-bodies 800 0.5 1 0 716"
    "sphere-pile 12 1.0 1 0 717" "box-stack 5 0.0 1 0 718" "wall 80 0.6 1000 0 719" "sphere-pile 10000 0.5 1 0 720")
fi
if [[ "${ROUND:-1}" == 6 ]]; then
  SPECS=(
    "sphere-pile 3500 0.6 1 0 801" "sphere-pile 7000 0.3 1 0 802" "sphere-pile 900 0.8 100 0.05 803"
    "box-stack 300 1.0 1 0 804" "box-stack 3000 0.5 10 0 805" "wall 500 0.4 1 0.1 806" "wall 1500 1.0 1 0 807"
    "tower 200 0.8 10 0 808" "tower 3000 1.2 1 0 809" "heavy-on-light 40 0.3 1000 0 810"
    "heavy-on-light 2000 1.0 10000 0 811" "mixed-shapes 300 0.7 1 0.1 812" "mixed-shapes 3500 0.8 1 0 813"
    "fem-block 300 0.6 1 0 814" "fem-block 2000 0.4 1 0 815" "fem-two-bodies 400 1.5 1 0 816"
    "sphere-pile 100 2.0 1 0 817" "box-stack 30 0.5 1 0.2 818" "wall 60 1.5 10 0 819" "sphere-pile 12000 0.6 1 0 820")
fi
if [[ "${ROUND:-1}" == 7 ]]; then
  SPECS=(
    "sphere-pile 2500 0.5 1 0 1001" "sphere-pile 5000 0.9 1 0.1 1002" "sphere-pile 600 0.3 10 0 1003"
    "box-stack 800 0.6 1 0 1004" "box-stack 60 1.8 100 0 1005" "wall 2000 0.7 1 0.05 1006" "wall 150 0.3 1 0 1007"
    "tower 1000 0.9 1 0 1008" "tower 80 2.0 1 0.1 1009" "heavy-on-light 300 0.5 10000 0 1010"
    "heavy-on-light 1000 1.2 100 0 1011" "mixed-shapes 1200 0.6 1 0 1012" "mixed-shapes 80 1.0 10 0.1 1013"
    "fem-block 800 0.7 1 0 1014" "fem-two-bodies 1000 0.4 1 0 1015" "fem-two-bodies 200 1.2 1 0 1016"
    "sphere-pile 8000 0.4 1 0 1017" "box-stack 12 0.9 1 0 1018" "sphere-pile 30 1.2 1 0.2 1019"
    "sphere-pile 2000 0.7 1000 0 1020")
fi
for spec in "${SPECS[@]}"; do
  set -- $spec
  base="$OUT/$1-$2-s$6"
  "$B" generate "$1" --contacts "$2" --mu "$3" --mass-ratio "$4" --penetration-correction "$5" --seed "$6" \
    --out "$base.hdf5" --local-out "$base-local.hdf5" > /dev/null 2>&1 || { echo "generate failed: $spec"; continue; }
  for p in "$base-local.hdf5" "$base.hdf5"; do
    t0=$(date +%s.%N)
    out=$(timeout 60 "$B" solve "$p" --tol 1e-8 --max-time 20 --json --out "${p%.hdf5}-sol.hdf5" 2>&1); rc=$?
    wall=$(python3 -c "import sys; print('%.2f' % ($(date +%s.%N) - $t0))")
    st=$(echo "$out" | python3 -c "import sys, json; d = json.load(sys.stdin); print(d['status'], d['solver'], d['iterations'], '%.2e' % d['error'], '%.3f' % d['seconds'])" 2>/dev/null)
    if [[ -f "$FCREF" ]]; then
      ref=$(OPENBLAS_NUM_THREADS=1 /usr/bin/python3 "$FCREF" "$p" "${p%.hdf5}-sol.hdf5" 2>&1 | tail -1)
    else
      ref="not checked ($FCREF not found; set FCREF)"
    fi
    echo "$(basename "$p") wall=$wall rc=$rc $st | fcref: $ref"
  done
done
