#!/usr/bin/env bash
# Applies the root .clang-format to every C++ source and header of the tree (Debian 12's
# clang-format 14, which scripts/install-deps.sh installs). ctest's format.* test checks it.
set -euo pipefail
cd "$(dirname "$0")/.."
git ls-files '*.cpp' '*.h' | xargs clang-format -i
