#!/usr/bin/env bash
# Builds chosen test binaries with sanitizers in their own build folders and runs them.
#   scripts/sanitizers.sh address [TEST_TARGET[:GTEST_FILTER]]...   ASan + UBSan (build-asan/)
#   scripts/sanitizers.sh thread  [TEST_TARGET[:GTEST_FILTER]]...   TSan (build-tsan/)
# Without targets: ASan+UBSan over the unit tests and the frame-fault test, TSan over the
# threaded integration tests (loop closing, realtime). Undefined behaviour stops the test
# (-fno-sanitize-recover). Exit status: non-zero when any binary fails. Not part of .ci/run: a
# sanitizer build of the whole project takes about an hour on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."

kind="${1:-address}"
shift || true
case "$kind" in
  address)
    build=build-asan
    flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g -O1"
    default_targets=(core_test io_test dynamic_test mapping_test frame_faults_test)
    export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:${ASAN_OPTIONS:-}"
    export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:${UBSAN_OPTIONS:-}"
    ;;
  thread)
    build=build-tsan
    flags="-fsanitize=thread -fno-omit-frame-pointer -g -O1"
    default_targets=(loop_closing_integration_test realtime_integration_test)
    export TSAN_OPTIONS="halt_on_error=0:second_deadlock_stack=1:${TSAN_OPTIONS:-}"
    ;;
  *)
    echo "usage: $0 address|thread [TEST_TARGET[:GTEST_FILTER]]..." >&2
    exit 2
    ;;
esac
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=("${default_targets[@]}")

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDRVSLAM_BUILD_BENCH=OFF \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="${flags%% *}" \
  -DCMAKE_SHARED_LINKER_FLAGS="${flags%% *}" >/dev/null

failed=0
for entry in "${targets[@]}"; do
  target="${entry%%:*}"
  filter="*"
  [[ "$entry" == *:* ]] && filter="${entry#*:}"
  cmake --build "$build" -j "$(nproc)" --target "$target" drvslam_cli
  echo "== $kind: $target --gtest_filter=$filter"
  if ! "$build/tests/$target" --gtest_filter="$filter"; then
    echo "== FAILED: $target" >&2
    failed=1
  fi
done
exit "$failed"
