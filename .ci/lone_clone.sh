#!/usr/bin/env bash
# The README's test command in a clone with nothing beside it (no ../shared),
# as a user who clones the repository has it: every test passes or skips.
# The clone compiles through the same ccache (scripts/build.sh sets its base
# directory to the checkout), so only the Python extension is rebuilt.
set -euo pipefail
cd "$(dirname "$0")/.."
lone=$(mktemp -d /tmp/fcsolve-lone.XXXXXX)
trap 'rm -rf "$lone"' EXIT
git clone --quiet . "$lone/fcsolve"
if [[ -e "$lone/shared" ]]; then echo "lone_clone: $lone/shared exists" >&2; exit 1; fi
cd "$lone/fcsolve"
bash scripts/test.sh
