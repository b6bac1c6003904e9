#!/usr/bin/env bash
# A generated development corpus (issue 13, item 3): about 65 problems taken
# along simulated trajectories by `fcsolve generate`, across every scene,
# nc from 10 to 10^4 (elastic scenes to 1500: their trajectory is solved by
# a Newton method that factorises at every iteration), mu from 0 to 2, mass ratios up to 10^4, with and
# without penetration correction. Written OUTSIDE the repository:
#   bash scripts/corpus.sh [OUT_DIR]     (default $FCSOLVE_CORPUS, else /tmp/fcsolve-corpus)
# Each problem is written as FC/I (NAME.hdf5) and as its FC/II reduction
# (NAME-local.hdf5) for rigid scenes and elastic ones up to 1000 contacts
# (an elastic scene's W is dense: 110 MB at 1000). OUT_DIR/MANIFEST.csv has one row per file:
#   file,scene,nc,n,mu,mass_ratio,penetration_correction,seed,kind,holdout,seconds
# n is the number of dofs of FC/I (also on the local file's row). Problems
# whose seed is a multiple of 3 (a third) are held out (holdout=1): tune on
# the others, check generalisation on those.
# FCSOLVE_CLI names the binary (default build/fcsolve, built if missing).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
OUT="${1:-${FCSOLVE_CORPUS:-/tmp/fcsolve-corpus}}"
case "$(realpath -m "$OUT")/" in
  "$ROOT"/*) echo "corpus.sh: $OUT is inside the repository; write the corpus elsewhere" >&2; exit 2 ;;
esac
CLI="${FCSOLVE_CLI:-$ROOT/build/fcsolve}"
if [[ ! -x "$CLI" ]]; then
  cmake -S "$ROOT" -B "$ROOT/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$ROOT/build" --target fcsolve_cli
fi
mkdir -p "$OUT"
manifest="$OUT/MANIFEST.csv"
echo "file,scene,nc,n,mu,mass_ratio,penetration_correction,seed,kind,holdout,seconds" > "$manifest"

# scene contacts mu mass_ratio (- = scene default) penetration_correction
specs=(
  "sphere-pile 10 0.5 - 0"    "sphere-pile 100 0.5 - 0"   "sphere-pile 1000 0.5 - 0"
  "sphere-pile 3000 0.5 - 0"  "sphere-pile 10000 0.5 - 0" "sphere-pile 300 0 - 0"
  "sphere-pile 300 2 - 0.2"   "sphere-pile 1000 0.3 100 0" "sphere-pile 100 1 - 0.5"
  "box-stack 10 0.5 - 0"      "box-stack 100 0.5 - 0"     "box-stack 1000 0.5 - 0"
  "box-stack 3000 0.5 - 0"    "box-stack 10000 0.5 - 0"   "box-stack 300 0 - 0"
  "box-stack 300 2 - 0.2"     "box-stack 1000 0.8 - 0.2"
  "wall 10 0.5 - 0"           "wall 100 0.5 - 0"          "wall 1000 0.5 - 0"
  "wall 3000 0.5 - 0"         "wall 10000 0.5 - 0"        "wall 300 0 - 0"
  "wall 300 2 - 0"            "wall 1000 0.7 100 0.2"
  "tower 10 0.5 - 0"          "tower 100 0.5 - 0"         "tower 1000 0.5 - 0"
  "tower 3000 0.5 - 0"        "tower 10000 0.5 - 0"       "tower 300 0 - 0"
  "tower 300 2 - 0.2"         "tower 1000 0.4 1000 0"
  "heavy-on-light 10 0.5 - 0" "heavy-on-light 100 0.5 10 0" "heavy-on-light 1000 0.5 - 0"
  "heavy-on-light 3000 0.5 1e4 0" "heavy-on-light 10000 0.5 - 0" "heavy-on-light 300 0 1e4 0"
  "heavy-on-light 300 2 100 0.2"  "heavy-on-light 1000 1 1e4 0.5"
  "fem-block 10 0.5 - 0"      "fem-block 100 0.5 - 0"     "fem-block 1000 0.5 - 0"
  "fem-block 500 0.5 - 0"     "fem-block 1500 0.5 - 0"   "fem-block 300 0 - 0"
  "fem-block 300 2 - 0.2"     "fem-block 1000 0.3 - 0.5"
  "fem-two-bodies 10 0.5 - 0" "fem-two-bodies 100 0.5 - 0" "fem-two-bodies 1000 0.5 - 0"
  "fem-two-bodies 500 0.5 - 0" "fem-two-bodies 1500 0.5 - 0" "fem-two-bodies 300 0 - 0"
  "fem-two-bodies 300 2 10 0.2" "fem-two-bodies 1000 0.6 100 0"
  "sphere-pile 30 0.5 - 0"    "box-stack 30 0.5 - 0"      "wall 30 0.5 - 0"
  "tower 30 0.5 - 0"
  "mixed-shapes 30 0.5 - 0"   "mixed-shapes 300 0.8 - 0.1" "mixed-shapes 1000 0.5 100 0"
  "mixed-shapes 3000 0.3 - 0"
)

start=$SECONDS
seed=0
for spec in "${specs[@]}"; do
  read -r scene contacts mu ratio beta <<<"$spec"
  seed=$((seed + 1))
  name=$(printf '%s-nc%s-s%02d' "$scene" "$contacts" "$seed")
  args=(generate "$scene" --contacts "$contacts" --seed "$seed" --mu "$mu" --penetration-correction "$beta"
        --out "$OUT/$name.hdf5")
  [[ "$ratio" != "-" ]] && args+=(--mass-ratio "$ratio")
  local_file=""
  if [[ "$scene" != fem-* || "$contacts" -le 1000 ]]; then
    local_file="$name-local.hdf5"
    args+=(--local-out "$OUT/$local_file")
  fi
  t0=$(date +%s.%N)
  line=$("$CLI" "${args[@]}")
  seconds=$(printf "%.3f" "$(echo "$(date +%s.%N) - $t0" | bc)")
  echo "$line"
  field() { sed -n "s/.* $1=\([^ ]*\).*/\1/p" <<<" $line"; }
  holdout=$((seed % 3 == 0 ? 1 : 0))
  row="$(field scene),$(field nc),$(field n),$(field mu),$(field mass_ratio),$(field penetration_correction),$seed"
  echo "$name.hdf5,$row,global,$holdout,$seconds" >> "$manifest"
  [[ -n "$local_file" ]] && echo "$local_file,$row,local,$holdout,$seconds" >> "$manifest"
done
echo "corpus.sh: $seed problems, $(($(wc -l < "$manifest") - 1)) files in $OUT ($((SECONDS - start)) s); manifest $manifest"
