#!/usr/bin/env bash
# The main job on a fresh machine: install what is missing, build the CLI,
# and solve the FCLIB problems bundled in examples/data with `auto` (the
# default solver), printing per problem its time and error beside the
# fastest single fcsolve solver's and Siconos' best (scripts/demo_table.py). Extra arguments
# go to demo_table.py (e.g. --tol 1e-10, --single-max-time 2).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
bash scripts/build.sh --target fcsolve_cli
export OPENBLAS_NUM_THREADS=1
/usr/bin/python3 scripts/demo_table.py --cli ./build/fcsolve examples/data/*.hdf5 "$@"
