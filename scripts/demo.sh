#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: install, build, run the default headless demo.
# Until the demo study lands, the demo renders one frame of the shooter scene and its buffers.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
out="${1:-demo-out}"
mkdir -p "$out"
build/app/warplab info --gl osmesa
build/app/warplab render --time 1.0 --width 1280 --height 720 --out "$out/frame.png" \
  --depth "$out/depth.png" --ids "$out/ids.png" --velocity "$out/velocity.png"
echo "demo: images in $out/"
