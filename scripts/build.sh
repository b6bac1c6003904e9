#!/usr/bin/env bash
# Configures and builds fcsolve in build/ (Release, Ninja, ccache when present).
# Extra arguments go to `cmake --build` (e.g. --target fcsolve_cli).
set -euo pipefail
cd "$(dirname "$0")/.."
export OPENBLAS_NUM_THREADS=1
# ccache keyed on paths relative to the checkout: another clone (CI's lone
# clone) reuses what this one compiled.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD} CCACHE_NOHASHDIR=1
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" "$@"
