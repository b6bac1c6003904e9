#!/usr/bin/env bash
# Every test on a fresh machine: install what is missing, pip-install the
# Python package into .venv (so `import fcsolve` works there), build
# everything, run the C++ and Python tests through CTest (its summary is the
# last line).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
bash scripts/python_venv.sh
bash scripts/build.sh
cd build
export OPENBLAS_NUM_THREADS=1
ctest --output-on-failure --no-tests=error -j"$(nproc)"
