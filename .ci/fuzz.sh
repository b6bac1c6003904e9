#!/usr/bin/env bash
# Fuzzing the FCLIB reader (fuzz/fuzz_fclib.cpp, libFuzzer + ASan + UBSan):
# replays the inputs that once found a bug (fuzz/regressions) and the hostile
# corpus, then fuzzes for SECONDS (default 60) from the seeds. Every failing
# input is replayed and classified (fuzz/classify.sh): a defect in fcsolve
# fails the job; one inside the HDF5 library (which fcsolve contains, see
# fuzz/regressions/README.md) is listed.
#   bash .ci/fuzz.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
bash scripts/deps.sh --fuzz
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD} CCACHE_NOHASHDIR=1
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_COMPILER=clang++ \
  -DFCSOLVE_BUILD_FUZZ=ON -DFCSOLVE_BUILD_TESTS=OFF -DFCSOLVE_BUILD_CLI=OFF \
  -DFCSOLVE_BUILD_PYTHON=OFF -DFCSOLVE_BUILD_BENCH=OFF -DFCSOLVE_BUILD_EXAMPLES=OFF >/dev/null
cmake --build build-fuzz --target fuzz_fclib
export OPENBLAS_NUM_THREADS=1
# A failed allocation returns NULL, as glibc's malloc does (the HDF5 library
# asks for 2^40+ bytes on some corrupt files and handles the failure).
export ASAN_OPTIONS=detect_leaks=0:allocator_may_return_null=1
fuzzer=build-fuzz/fuzz/fuzz_fclib
shopt -s nullglob
# In-process replay: all but the inputs that crash the HDF5 library itself
# (those are checked through the CLI's isolated read, tests/cli/test_hostile.py).
replay=()
for f in fuzz/regressions/*.hdf5 tests/hostile/files/*.hdf5; do
  case $(basename "$f") in
    libhdf5-local-heap-null-read-*|libhdf5-runaway-alloc-*|libhdf5-contig-read-null-memcpy*) ;;
    *) replay+=("$f") ;;
  esac
done
"$fuzzer" -rss_limit_mb=2048 -timeout=60 "${replay[@]}" 2>&1 | tail -3
work=$(mktemp -d /tmp/fcsolve-fuzz.XXXXXX)
trap 'rm -rf "$work"' EXIT
mkdir "$work/corpus" "$work/artifacts"
# libFuzzer's fork mode exits with its last job's status (71 after an
# out-of-memory input, 70 after a timeout, 77 after a crash) even when told
# to go on; the verdict is the classification of the artifacts below.
status=0
"$fuzzer" -fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1 \
  -max_total_time="$seconds" -max_len=200000 -rss_limit_mb=2048 -timeout=20 \
  -artifact_prefix="$work/artifacts/" "$work/corpus" fuzz/seeds tests/hostile/files \
  >"$work/log" 2>&1 || status=$?
grep -E '^#[0-9]+:|^INFO: fuzzed|^INFO: exiting|DONE|stat::' "$work/log" | tail -4 || true
echo "fuzz: libFuzzer exited with status $status"
if ! grep -qE '^INFO: fuzzed for|^INFO: exiting' "$work/log"; then
  echo "fuzz: the fuzzer did not run to its time limit:" >&2; tail -20 "$work/log" >&2; exit 1
fi
failures=("$work"/artifacts/*)
echo "fuzz: ${#failures[@]} failing inputs to classify"
if (( ${#failures[@]} )); then
  bash fuzz/classify.sh "$fuzzer" "${failures[@]}"
fi
