#!/usr/bin/env bash
# Replay speed, a benchmark rather than a timed test: plays a full shooter-thesis session
# headlessly with the bot (acclimation, training, 675 test targets), then replays it without
# rendering and prints how many times faster than real time the replay ran.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${WARPLAB_BUILD_DIR:-build}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
session=$("$build/app/warplab" run --protocol protocol/shooter-thesis.json --participant bench \
  --out "$out" --headless --player bot:1 --seed 1 2>/dev/null)
for i in 1 2 3; do
  "$build/app/warplab" replay "$session"
done
