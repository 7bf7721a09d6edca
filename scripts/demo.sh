#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: install, build, and run `warplab demo` -- a small
# simulated study, headless: 8 perceptual simulated participants play shooter-demo and
# click-demo, every session is replayed and checked, exported to CSVs and analysed into a
# report with figures and a sample-size plan. Then a few seconds of one simulated session are
# redrawn as its modes showed them, and one frame is written with its buffers.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
out="${1:-demo-out}"
warplab=build/app/warplab
$warplab info --gl osmesa
$warplab demo --out "$out"
# What the first simulated participant saw of the shooter test (the frames at 120 Hz, with the
# reticle and HIT/MISS banner), redrawn from its session and checked against the scoring.
session=$(sed -n 's/^demo-session\t//p' "$out/logs/sim-1-shooter-demo.log")
$warplab replay "$session" --render "$out/frames" --frames 3600:3839 --width 640 --height 360
$warplab render --time 1.0 --width 1280 --height 720 --out "$out/frame.png" \
  --depth "$out/depth.png" --ids "$out/ids.png" --velocity "$out/velocity.png"
echo "demo: sessions in $out/results (logs in $out/logs), CSVs in $out/export,"
echo "demo: the report in $out/report/report.md, displayed frames in $out/frames, a frame and its buffers in $out/"
