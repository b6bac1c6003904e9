#!/usr/bin/env bash
# The main job on a fresh machine: install what is missing, build the CLI,
# and solve the FCLIB problems bundled in examples/data with the NSGS
# variants, printing a table (problem, nc, solver, status, iterations, error,
# seconds).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
bash scripts/build.sh --target fcsolve_cli
./build/fcsolve run examples/data/*.hdf5 "$@"
