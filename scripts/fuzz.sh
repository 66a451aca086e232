#!/usr/bin/env bash
# Fuzzes the whole path from OBJ + MTL text to a rendered 16x16 frame (tests/fuzz/fuzz_scene_to_frame.cpp) with
# libFuzzer under AddressSanitizer + UndefinedBehaviorSanitizer, in build-fuzz/ (clang).
#   scripts/fuzz.sh            # 60 seconds (FUZZ_SECONDS=N for longer; CI uses the default)
# It first replays the committed corpus in tests/fuzz/corpus (seeds and every input that ever crashed) and the
# hostile scenes in tests/hostile, then
# mutates. Fails on any crash, sanitizer report, leak, uncaught exception, hang (-timeout) or memory blow-up
# (-rss_limit_mb). A failing input is saved under build-fuzz/artifacts/: fix the bug, then commit that file to
# tests/fuzz/corpus/ as a regression case. New interesting inputs go to build-fuzz/corpus/, not to the repo.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
lueur_install_packages

FUZZ_SECONDS="${FUZZ_SECONDS:-60}"
build="$LUEUR_ROOT/build-fuzz"
if [ ! -f "$build/build.ninja" ]; then
  CC=clang CXX=clang++ cmake -S "$LUEUR_ROOT" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DLUEUR_BUILD_TESTS=OFF -DLUEUR_FUZZ=ON -DLUEUR_SANITIZE=address,undefined >&2
fi
cmake --build "$build" --parallel "$(nproc)" --target fuzz_scene_to_frame >&2

mkdir -p "$build/corpus" "$build/artifacts"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:${UBSAN_OPTIONS:-}"
echo "lueur: fuzzing for ${FUZZ_SECONDS} s" >&2
status=0
"$build/tests/fuzz/fuzz_scene_to_frame" -max_total_time="$FUZZ_SECONDS" -timeout=20 -rss_limit_mb=2048 \
  -max_len=16384 -dict="$LUEUR_ROOT/tests/fuzz/obj.dict" -artifact_prefix="$build/artifacts/" -print_final_stats=1 \
  "$build/corpus" "$LUEUR_ROOT/tests/fuzz/corpus" "$LUEUR_ROOT/tests/hostile" || status=$?
if [ "$status" -ne 0 ]; then
  echo "lueur: the fuzzer found a problem (exit status $status); the input is in $build/artifacts/" >&2
  exit 1
fi
echo "lueur: fuzzing found nothing in ${FUZZ_SECONDS} s" >&2
