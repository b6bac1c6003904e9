#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer (gcc, -O1) build of the
# reader and problem tests (fcsolve_tests: reader, hostile corpus, problems,
# error, reduction, VI) and of the CLI, which holds the whole catalogue. Runs
# fcsolve_tests, the CLI's end-to-end tests and hostile corpus, and every
# catalogue entry (every family) through the CLI on a local and a global
# bundled problem. Any sanitizer report fails the job. (The catalogue-wide
# contract test runs in the main build: under ASan its compile alone would
# take a quarter of CI's time budget.)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
flags="-O1 -g -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD} CCACHE_NOHASHDIR=1
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DFCSOLVE_BUILD_PYTHON=OFF -DFCSOLVE_BUILD_BENCH=OFF -DFCSOLVE_BUILD_EXAMPLES=OFF >/dev/null
cmake --build build-asan -j"$(nproc)" --target fcsolve_cli fcsolve_tests
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1 FCSOLVE_SANITIZED=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:exitcode=99
export OPENBLAS_NUM_THREADS=1
build-asan/tests/fcsolve_tests
cli=$PWD/build-asan/fcsolve
FCSOLVE_CLI=$cli /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/cli/test_cli.py tests/cli/test_hostile.py
# One line per entry: name and whether it solves FC/II (global-only entries
# are run on the global problem only).
entries=$("$cli" solvers --json | /usr/bin/python3 -c "
import json, sys
for e in json.load(sys.stdin): print(e['name'], int(e['local']))")
runs=0
while read -r solver local; do
  problems=(examples/data/GFC3D_Example1.hdf5)
  (( local )) && problems+=(examples/data/Rover1039.hdf5)
  for problem in "${problems[@]}"; do
    status=0
    "$cli" solve "$problem" --solver "$solver" --max-time 20 </dev/null >/dev/null || status=$?
    # 0 solved, 1 not solved: fine; 2 is bad input (none here); a sanitizer
    # report aborts (ASan) or exits 99 (UBSan)
    if (( status > 1 )); then echo "sanitizers: $solver on $problem exited $status" >&2; exit 1; fi
    runs=$((runs + 1))
  done
done <<<"$entries"
echo "sanitizers: $runs catalogue runs clean ($(cut -d' ' -f1 <<<"$entries" | tr '\n' ' '))"
