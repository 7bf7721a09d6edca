#!/usr/bin/env bash
# Re-renders every reference image (tests/references/*.png) from the current code. Look at
# the failing test's .actual.png and .diff.png in build/test-output/ first; approve only a
# change you meant, and commit the new references with the change that caused them.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${WARPLAB_BUILD_DIR:-build}"
cmake --build "$build" --target warplab_gl_tests warplab_cli_tests -j"$(nproc)"
WARPLAB_APPROVE=1 "$build/tests/warplab_gl_tests" --gtest_filter='*Reference*'
# The live-session screens (start, a shot, the pause, a rating, the end), made under Xvfb.
WARPLAB_APPROVE=1 "$build/tests/warplab_cli_tests" \
  --gtest_filter='LiveSession.AScriptedParticipant*:LiveSession.TheBotInTheWindow*'
git status --short tests/references
