#!/usr/bin/env bash
# A benchmark campaign on a fresh machine, in one command: installs what is
# missing, builds the CLI, runs every registered solver on the FCLIB problems
# bundled in examples/data, and writes campaign/results.csv and the report
# (campaign/report/report.html and its PNGs).
#   bash scripts/campaign.sh                                  # defaults below
#   bash scripts/campaign.sh --tol 1e-4,1e-8 --solvers all,siconos:all
#   PROBLEMS=../shared/data/fclib bash scripts/campaign.sh --out campaign-shared
# Extra arguments go to `fcsolve bench` (see `build/fcsolve bench --help`).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
bash scripts/build.sh --target fcsolve_cli
export OPENBLAS_NUM_THREADS=1
# shellcheck disable=SC2086  # PROBLEMS may name several paths
./build/fcsolve bench ${PROBLEMS:-examples/data} --out campaign --tol 1e-4,1e-6,1e-8 --timeout 20 \
  --report "$@"
