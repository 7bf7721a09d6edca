#!/usr/bin/env bash
# The test job on a fresh Debian 12 machine: install, build (warnings are errors), run every
# test. .ci/run calls exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh -DWARPLAB_WERROR=ON
cd "${WARPLAB_BUILD_DIR:-build}"
ctest --output-on-failure -j2
