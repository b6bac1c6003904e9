#!/usr/bin/env bash
# Every test as a lone clone has them, with no ../shared beside it: the
# tests of the build that scripts/test.sh just made are run again with
# FCSOLVE_SHARED_DATA pointing at an empty place (every test program, pytest
# suite and conftest reads it before looking for ../shared); each test must
# pass or skip with a reason. Then a real `git clone` is checked for what
# those tests read from the repository (bundled problems, hostile corpus).
# (A full rebuild in a second clone would cost a third of CI's budget: the
# test programs' data paths are compiled in, so ccache cannot share them.)
set -euo pipefail
cd "$(dirname "$0")/.."
empty=$(mktemp -d /tmp/fcsolve-no-shared.XXXXXX)
trap 'rm -rf "$empty"' EXIT
export FCSOLVE_SHARED_DATA=$empty/data/fclib OPENBLAS_NUM_THREADS=1
(cd build && ctest --output-on-failure --no-tests=error -j"$(nproc)")
git clone --quiet . "$empty/fcsolve"
for needed in examples/data/Rover1039.hdf5 examples/data/GFC3D_Example1.hdf5 \
              tests/hostile/files/MANIFEST.json fuzz/seeds/Rover1039.hdf5; do
  [[ -f "$empty/fcsolve/$needed" ]] || { echo "lone_clone: a clone lacks $needed" >&2; exit 1; }
done
echo "lone_clone: every test passes or skips without ../shared"
