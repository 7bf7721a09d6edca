#!/usr/bin/env bash
# The test job on a fresh Debian 12 machine: install, build (warnings are errors), run every
# test. .ci/run calls exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh

# Sanitizer tier: the tests that need no GL context (every module's label "unit" binary),
# built with AddressSanitizer and UndefinedBehaviorSanitizer (Mesa's JIT is left out of it on
# purpose).
asan="${WARPLAB_ASAN_BUILD_DIR:-build-asan}"
cmake -S . -B "$asan" -DWARPLAB_SANITIZE=ON -DCMAKE_BUILD_TYPE=Debug -DWARPLAB_WERROR=ON >/dev/null
cmake --build "$asan" --target warplab_unit_tests -j"$(nproc)"
ctest --test-dir "$asan" -L unit -j"$(nproc)" --output-on-failure
# Fuzz smoke: the protocol parser and the session reader, 30 s each under ASan/UBSan (docs/fuzzing.md).
scripts/fuzz.sh 30

# Everything, optimised: unit, GL (headless), CLI, window (Xvfb) and analysis tests. The same
# optimisation as build.sh's RelWithDebInfo, without its debug information: nobody debugs a CI
# build, and writing and linking the debug sections is a good part of a two-core machine's time.
scripts/build.sh -DWARPLAB_WERROR=ON -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -DNDEBUG" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -DNDEBUG"
cd "${WARPLAB_BUILD_DIR:-build}"
ctest --output-on-failure -j2
