#!/usr/bin/env bash
# Installs the Debian packages fcsolve needs, and only those missing: quiet
# and without touching apt when everything is there (idempotent).
#   bash scripts/deps.sh            build + test dependencies
#   bash scripts/deps.sh --peers    also Siconos 4.4 (python3-siconos), the peer
#                                   the benchmark scripts compare against
#   bash scripts/deps.sh --fuzz     also clang and its sanitizer runtimes
#                                   (libFuzzer: fuzz/, .ci/fuzz.sh)
set -euo pipefail

packages=(
  g++ cmake ninja-build pkg-config ccache
  libeigen3-dev libsuitesparse-dev libopenblas-dev libhdf5-dev
  catch2 libbenchmark-dev pybind11-dev
  python3-dev python3-venv python3-pip python3-numpy python3-scipy python3-h5py python3-pytest
  python3-matplotlib                    # campaign reports (fcsolve report)
  python3-dask python3-distributed      # campaigns on a Dask cluster (fcsolve bench --dask)
)
for option in "$@"; do
  case "$option" in
    --peers) packages+=(python3-siconos) ;;
    --fuzz) packages+=(clang libclang-rt-dev) ;;
    *) echo "deps.sh: unknown option $option (--peers, --fuzz)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

sudo=""
if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
echo "fcsolve: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
# --no-install-recommends: libsuitesparse-dev recommends libgraphblas-dev (+500 MB)
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
