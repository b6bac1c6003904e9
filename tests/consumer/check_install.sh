#!/usr/bin/env bash
# Installs the fcsolve build tree into a scratch prefix, builds the consumer
# project against it with find_package(fcsolve CONFIG) and runs it.
#   check_install.sh BUILD_DIR SOURCE_DIR SCRATCH_DIR
set -euo pipefail
build=$1 src=$2 scratch=$3
rm -rf "$scratch"
cmake --install "$build" --prefix "$scratch/prefix" >/dev/null
cmake -S "$src/tests/consumer" -B "$scratch/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$scratch/prefix" -DCMAKE_CXX_COMPILER_LAUNCHER= >/dev/null
cmake --build "$scratch/build" >/dev/null
"$scratch/build/consumer" "$src/examples/data/Rover1039.hdf5"
# The installed CLI reaches its installed campaign runner (fcsolve bench/report).
if [[ -x "$scratch/prefix/bin/fcsolve" ]]; then
  test -f "$scratch/prefix/share/fcsolve/python/fcsolve/campaign/__main__.py"
  "$scratch/prefix/bin/fcsolve" bench --help | grep -q -- "--solvers"
fi
