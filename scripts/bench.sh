#!/usr/bin/env bash
# Builds and runs every Google Benchmark program (build/bench/bench_*), with
# counters; results also go to bench/results/<program>.json.
#   bash scripts/bench.sh                               # all, short runs
#   bash scripts/bench.sh --benchmark_filter=Storage    # any Google Benchmark option
# Default --benchmark_min_time=0.01 (Google Benchmark 1.7 wants a plain
# number of seconds). Timings on a shared machine are noisy: compare ratios
# within one run.
set -euo pipefail
cd "$(dirname "$0")/.."
export OPENBLAS_NUM_THREADS=1
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target fcsolve_benchmarks
args=("$@")
[[ " ${args[*]} " == *" --benchmark_min_time"* ]] || args+=(--benchmark_min_time=0.01)
mkdir -p bench/results
status=0
for program in build/bench/bench_*; do
  [[ -x "$program" && -f "$program" ]] || continue
  name=$(basename "$program")
  echo "== $name"
  "$program" "${args[@]}" --benchmark_out="bench/results/$name.json" \
    --benchmark_out_format=json || status=1
done
exit $status
