#!/usr/bin/env bash
# Runs the test suite under the sanitizers, each build in its own directory (clang, -fno-sanitize-recover=all):
#   build-asan/  every test under AddressSanitizer + UndefinedBehaviorSanitizer (leaks included)
#   build-tsan/  the threading tests (thread pool, renderer, tracer thread, BVH build) under ThreadSanitizer
#   scripts/sanitize.sh [asan|tsan]   # both by default
# Tests also start the `lueur` executable, built with the same sanitizers: every process writes its reports to
# <build>/sanitizer-logs/, and any file there fails the run, whatever the exit statuses said.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
lueur_install_packages

# Threading tests: the thread pool, the renderer across thread counts and cancelled from another thread, the
# viewer's tracer thread (its stress test included), the BVH's parallel build, the OBJ read, the smooth normals and
# the textures on every core, the loading line's redrawing thread, and the L1 store's records from every thread (ln's
# further light among them).
# Embree's own threads are not instrumented, so its tests stay out.
TSAN_TARGETS=(test_thread_pool test_render test_indirect test_progressive test_bvh_brute_force test_bvh_degenerate
  test_obj_chunks test_smooth_normals test_textures test_load_progress test_store_learning)
TSAN_TESTS='ThreadPool|CancelledFrame|Render\.BitIdentical|ReuseFraction|ProgressiveTracer|Bvh|ObjChunks|SmoothNormals|TextureLoading|LoadProgressLine|StoreServesLn\.AreTheSameBytes'

# The tests that draw through OpenGL (Mesa) in-process or in the lueur processes they start.
GL_TESTS='GlDisplay|Window\.UnderXvfb'

sanitized_build() {  # build_dir sanitizers [cmake --build arguments...]
  local dir="$1" sanitizers="$2"
  shift 2
  if [ ! -f "$dir/build.ninja" ]; then
    CC=clang CXX=clang++ cmake -S "$LUEUR_ROOT" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DLUEUR_SANITIZE="$sanitizers" >&2
  fi
  cmake --build "$dir" --parallel "$(nproc)" "$@" >&2
}

run_checked() {  # build_dir ctest arguments...
  local dir="$1"
  shift
  local logs="$dir/sanitizer-logs"
  rm -rf "$logs"
  mkdir -p "$logs"
  chmod 1777 "$logs"  # some tests run lueur as the user nobody
  local status=0
  (
    cd "$dir"
    ASAN_OPTIONS="log_path=$logs/asan:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1${ASAN_EXTRA:-}" \
      UBSAN_OPTIONS="log_path=$logs/ubsan:print_stacktrace=1:halt_on_error=1" \
      TSAN_OPTIONS="log_path=$logs/tsan:halt_on_error=1:second_deadlock_stack=1" \
      ctest --output-on-failure -j "$(nproc)" --timeout 1200 "$@"
  ) || status=$?
  if [ -n "$(ls -A "$logs")" ]; then
    echo "lueur: sanitizer reports in $logs:" >&2
    for f in "$logs"/*; do
      echo "==== $f" >&2
      head -c 20000 "$f" >&2
    done
    status=1
  fi
  return "$status"
}

what="${1:-all}"
if [ "$what" = all ] || [ "$what" = asan ]; then
  echo "lueur: every test under AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/)" >&2
  sanitized_build "$LUEUR_ROOT/build-asan" address,undefined
  run_checked "$LUEUR_ROOT/build-asan" -E "$GL_TESTS"
  # Mesa's GL drivers (EGL, OSMesa, llvmpipe) leak at exit, are built without frame pointers and unload
  # themselves, so their leak reports can be neither traced nor suppressed: the GL tests run without leak
  # detection, with every other address and undefined-behaviour check still on.
  ASAN_EXTRA=":detect_leaks=0" run_checked "$LUEUR_ROOT/build-asan" -R "$GL_TESTS"
fi
if [ "$what" = all ] || [ "$what" = tsan ]; then
  echo "lueur: the threading tests under ThreadSanitizer (build-tsan/)" >&2
  sanitized_build "$LUEUR_ROOT/build-tsan" thread --target "${TSAN_TARGETS[@]}"
  run_checked "$LUEUR_ROOT/build-tsan" -R "$TSAN_TESTS"
fi
echo "lueur: no sanitizer reports" >&2
