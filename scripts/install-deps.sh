#!/usr/bin/env bash
# Installs everything warplab needs to build, run and test on Debian 12, with apt-get.
# Run as root (or with sudo). Safe to run again.
set -euo pipefail

packages=(
  # build
  cmake g++ make pkg-config
  # windowing, GL headers and loaders: SDL2 window, OSMesa and EGL headless contexts
  libsdl2-dev libsdl2-ttf-dev fonts-dejavu-core
  # Xlib: the window's X errors (its window destroyed by another program, the X server gone)
  # said in a sentence rather than by Xlib's default handlers (renderer/src/x11_errors.h)
  libx11-dev
  libgl-dev libegl-dev libegl1-mesa-dev libosmesa6-dev libgl1-mesa-dri mesa-common-dev
  # libraries
  libglm-dev libtinyobjloader-dev nlohmann-json3-dev libstb-dev libsqlite3-dev
  # SHA-256 of frame-time trace files (libcrypto)
  libssl-dev
  # tests: GoogleTest, a virtual X server for the window tests, and xdotool to unmap, focus,
  # type into and destroy a window as a window manager or another program would
  libgtest-dev xvfb xauth xdotool
  # fuzzing (scripts/fuzz.sh): clang; libclang-rt-14-dev holds libFuzzer and the sanitizer
  # runtimes (libclang_rt.fuzzer-x86_64.a ...); llvm-14 the symbolizer for readable reports
  clang libclang-rt-14-dev llvm-14
  # the house style (.clang-format; scripts/format.sh, and a ctest that checks the tree)
  clang-format
  # analysis scripts run with Debian's /usr/bin/python3 and these (statsmodels: the click
  # game's repeated-measures ANOVA)
  python3 python3-numpy python3-scipy python3-pandas python3-matplotlib python3-pytest python3-statsmodels
  # R and exactRankTests: the analysis tests check the report's statistics against R's
  # (analysis/tests/test_against_r.py) and run the docs' R snippets (test_doc_snippets.py)
  r-base-core r-cran-exactranktests
  # psyphy: the psychometric fit is checked against glm with its forced-choice links
  # (analysis/tests/test_psychometric.py)
  r-cran-psyphy
  # the report's trial-level mixed models (analysis/r/mixed_models.R): lme4's GLMMs, emmeans'
  # marginal means and contrasts, ordinal's cumulative-link models, jsonlite for the results;
  # glmmTMB fits them independently in analysis/tests/test_mixed_models.py
  r-cran-lme4 r-cran-emmeans r-cran-ordinal r-cran-jsonlite r-cran-glmmtmb
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
