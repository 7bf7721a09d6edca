#!/usr/bin/env bash
# Fuzzes the protocol parser and the session reader (tests/fuzz/, docs/fuzzing.md): builds the
# libFuzzer targets with clang, AddressSanitizer and UndefinedBehaviorSanitizer, then runs each
# for SECONDS (default 30) on a scratch copy of its seed corpus. Exits non-zero when a target
# finds a crash, a sanitizer report, a leak or a hang; the input that did it is left in
# BUILD/fuzz-work/findings/TARGET/ and the log beside it.
#
# usage: scripts/fuzz.sh [SECONDS]
#   WARPLAB_FUZZ_BUILD_DIR  build folder (default build-fuzz); BUILD/fuzz-work is remade each run
set -euo pipefail
cd "$(dirname "$0")/.."

seconds="${1:-30}"
if ! [[ "$seconds" =~ ^[1-9][0-9]*$ ]] || [ $# -gt 1 ]; then
  echo "usage: scripts/fuzz.sh [SECONDS]  (each target's fuzzing time, a whole number >= 1; default 30)" >&2
  exit 2
fi
build="${WARPLAB_FUZZ_BUILD_DIR:-build-fuzz}"

# -O1 with assertions on (libstdc++'s bounds checks, nlohmann's JSON_ASSERT): fast enough to
# fuzz, and a broken precondition stops the input instead of passing silently. Warnings are not
# errors here: the libraries are held to -Werror under g++ (scripts/test.sh), and what clang
# alone warns about must not stop the fuzzing; the targets themselves are always -Werror.
cmake -S . -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DWARPLAB_FUZZ=ON \
  -DWARPLAB_WERROR=OFF -DBUILD_TESTING=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g" "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g -D_GLIBCXX_ASSERTIONS" >/dev/null
cmake --build "$build" --target warplab_fuzz_protocol warplab_fuzz_session -j"$(nproc)"

# Everything a run writes stays in here: the corpora grow in a copy, never in the source tree,
# and TMPDIR points here so a crashed session target's temporary folder goes with the rest.
work="$build/fuzz-work"
rm -rf "$work"
mkdir -p "$work/tmp"
export TMPDIR="$PWD/$work/tmp"
# Symbolized stacks in reports (llvm-14 ships the symbolizer as llvm-symbolizer-14 only).
if [ -z "${ASAN_SYMBOLIZER_PATH:-}" ]; then
  symbolizer="$(command -v llvm-symbolizer || command -v llvm-symbolizer-14 || true)"
  [ -z "$symbolizer" ] || export ASAN_SYMBOLIZER_PATH="$symbolizer"
fi
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"

# Protocol keys, enum values and mode ids, quoted as JSON writes them: the parsers' own string
# literals and the shipped protocols', so the dictionary follows the code without a list to keep.
grep -ohE '"[A-Za-z0-9_.+-]{2,40}"' games/*/src/*_protocol.cpp protocol/src/fields.cpp condition/src/condition.cpp \
  protocol/*.json tests/fuzz/corpus/protocol/*.json |
  sort -u | sed 's/"/\\"/g; s/.*/"&"/' >"$work/protocol.dict"

failed=0
# fuzz TARGET MAX_LEN [LIBFUZZER_FLAG...] -- SEED...
fuzz() {
  local target="$1" max_len="$2"
  shift 2
  local flags=()
  while [ "$1" != "--" ]; do flags+=("$1"); shift; done
  shift
  local corpus="$work/corpus/$target" findings="$work/findings/$target" log="$work/$target.log"
  mkdir -p "$corpus" "$findings"
  cp "$@" "$corpus/"
  local rc=0
  "$build/tests/fuzz/$target" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len="$max_len" -artifact_prefix="$findings/" -print_final_stats=1 "${flags[@]}" >"$log" 2>&1 || rc=$?
  local runs rate added
  runs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")"
  rate="$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")"
  added="$(sed -n 's/^stat::new_units_added: *//p' "$log")"
  if [ "$rc" -eq 0 ]; then
    echo "fuzz: $target: ${runs:-?} executions in $seconds s (${rate:-?}/s), ${added:-?} new corpus inputs, no findings"
  else
    failed=1
    echo "fuzz: $target: FAILED (exit $rc) after ${runs:-?} executions; log $log, reproducer(s):"
    ls -1 "$findings" | sed "s|^|  $findings/|"
    echo "  reproduce: $build/tests/fuzz/$target FILE   (docs/fuzzing.md)"
    # From the report on (the target's own sentence, a sanitizer's or libFuzzer's), else the end.
    local from
    from="$(grep -n -m1 -E '^fuzz_(protocol|session): |^==[0-9]+==ERROR|runtime error: |^ERROR: libFuzzer' "$log" | cut -d: -f1)"
    echo "---- $log ----"
    if [ -n "$from" ]; then tail -n +"$from" "$log" | head -n 80; else tail -n 40 "$log"; fi
    echo "----"
  fi
}

# Protocols are a few kilobytes; 16 KiB leaves room to grow them without slowing every run.
# (The 1 MiB size and 32-level depth limits in protocol/include/protocol/fields.h are unit-tested.)
fuzz warplab_fuzz_protocol 16384 -dict="$work/protocol.dict" -- \
  protocol/*.json tests/fuzz/corpus/protocol/*.json
# Session files are SQLite pages of 4 KiB; 96 KiB holds the committed seeds whole and cuts the
# version-1 and version-2 sessions (570 KiB, 1.3 MiB) short, which are truncated files the
# reader must also handle.
fuzz warplab_fuzz_session 98304 -- \
  tests/fuzz/corpus/session/*.warplab-session tests/data/v1-shooter-quick.warplab-session \
  tests/data/v2-click-quick.warplab-session

exit "$failed"
