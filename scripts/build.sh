#!/usr/bin/env bash
# Configures and builds fcsolve in build/ (Release, Ninja, ccache when present).
# Extra arguments go to `cmake --build` (e.g. --target fcsolve_cli).
set -euo pipefail
cd "$(dirname "$0")/.."
export OPENBLAS_NUM_THREADS=1
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" "$@"
