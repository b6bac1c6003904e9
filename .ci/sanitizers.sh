#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer (gcc, -O1) build of the
# reader and problem tests (fcsolve_tests), the catalogue-wide contract test
# (every solver family), and the CLI, run on the CLI's end-to-end tests and
# the hostile corpus. Any sanitizer report fails the job.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
flags="-O1 -g -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD} CCACHE_NOHASHDIR=1
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DFCSOLVE_BUILD_PYTHON=OFF -DFCSOLVE_BUILD_BENCH=OFF -DFCSOLVE_BUILD_EXAMPLES=OFF >/dev/null
cmake --build build-asan -j"$(nproc)" --target fcsolve_cli fcsolve_tests fcsolve_contract_tests
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1 FCSOLVE_SANITIZED=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export OPENBLAS_NUM_THREADS=1
build-asan/tests/fcsolve_tests
build-asan/tests/fcsolve_contract_tests
FCSOLVE_CLI=$PWD/build-asan/fcsolve /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/cli/test_cli.py tests/cli/test_hostile.py
