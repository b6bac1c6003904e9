#!/usr/bin/env bash
# The Python package as a user installs it: a virtual environment .venv made
# from Debian's python3 with --system-site-packages (Debian's numpy, scipy,
# h5py, pytest serve; pyenv's python3 on PATH has none of them), then
# `pip install .` (scikit-build-core drives python/CMakeLists.txt; its build
# requirements, scikit-build-core and pybind11 >= 2.12, come from PyPI).
# Afterwards `.venv/bin/python -c "import fcsolve"` works, and CTest's
# python_pip_pytest runs the module's tests against this installed copy.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=.venv
if [[ ! -x $venv/bin/python ]]; then
  /usr/bin/python3 -m venv --system-site-packages "$venv"
fi
echo "fcsolve: pip install . into $venv (builds the extension, a few minutes)" >&2
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check .
"$venv/bin/python" -c "import fcsolve; print('fcsolve', fcsolve.__version__, 'in', fcsolve.__file__)"
