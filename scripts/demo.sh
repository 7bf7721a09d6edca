#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: install, build, run the default headless demo
# studies -- the quick shooter and click-game protocols played by their scripted bots,
# replayed and checked, a few seconds of each re-rendered as its modes showed it, four bot
# participants per game exported and analysed into a report -- plus one rendered frame with
# its buffers.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
out="${1:-demo-out}"
mkdir -p "$out/results"
warplab=build/app/warplab
$warplab info --gl osmesa
session=$($warplab run --protocol protocol/shooter-quick.json --participant demo --out "$out/results" \
  --headless --player bot:1)
echo "demo: session $session"
$warplab replay "$session" --render "$out/frames" --frames 600:839 --width 640 --height 360
click=$($warplab run --protocol protocol/click-quick.json --participant demo --out "$out/results" \
  --headless --player bot:1)
echo "demo: click-game session $click"
$warplab replay "$click" --render "$out/click-frames" --frames 20:259 --width 640 --height 360
# Three more bot participants per game, so that the paired tests have pairs to test.
for seed in 2 3 4; do
  for protocol in shooter-quick click-quick; do
    $warplab run --protocol protocol/$protocol.json --participant "bot$seed" --out "$out/results" \
      --headless --player bot:$seed --seed $seed > /dev/null
  done
done
$warplab export "$out/results" --out "$out/export"
analysis/analyze "$out/export" --out "$out/report"
$warplab render --time 1.0 --width 1280 --height 720 --out "$out/frame.png" \
  --depth "$out/depth.png" --ids "$out/ids.png" --velocity "$out/velocity.png"
echo "demo: sessions in $out/results, displayed frames in $out/frames and $out/click-frames,"
echo "demo: CSVs in $out/export, the report in $out/report/report.md, a frame and its buffers in $out/"
