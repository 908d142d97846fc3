#!/usr/bin/env bash
# The sanitizer jobs (.ci/run runs both, after the release build, the tests and the demo).
#   scripts/sanitizers.sh address [TEST_TARGET[:GTEST_FILTER]]...   ASan + UBSan, in build-asan/
#   scripts/sanitizers.sh thread  [TEST_TARGET[:GTEST_FILTER]]...   TSan, in build-tsan/
# Without targets, the default set below: ASan+UBSan over the unit and integration tests, TSan
# over the threaded ones (loop closing, dense mapper, async segmenter, realtime, local mapping,
# the extraction helper, reset when lost, the queues). The filters leave out the slowest runs
# whose code paths other tests cover; each one says why.
#
# Kept cheap for a 2-core CI machine (cmake/DrvslamSanitizers.cmake): only the chosen test
# binaries and the CLI they run are built, at -O1 -g1 as a unity build, without the benchmarks or
# the Python module; the release build's default vocabulary (build/) is copied instead of being
# trained again. The address tree is compiled with clang-16 (Debian's, which
# scripts/install-deps.sh installs): it compiles instrumented code in about half GCC 12's time
# (drvslam_optim's batch: 58 CPU-s against 112 with ASan), and the fuzz targets (fuzz/) need it.
# Binaries run two at a time.
# Every report of every process, the CLI runs the tests start included, goes to a log file: any
# report fails the job (exit status 1) and is printed. Undefined behaviour stops the program
# (-fno-sanitize-recover). Both need the release build first (its vocabulary, and its CLI
# renders the integration tests' sequences).
# Third-party false positives go in scripts/sanitizers/{lsan,tsan}.supp, each with its reason.
# Options given in ASAN_OPTIONS, UBSAN_OPTIONS or TSAN_OPTIONS come last and win (for example
# ASAN_OPTIONS=detect_leaks=0 to look past a known leak).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

kind="${1:-}"
run_prefix=()
generator=()
export ASAN_OPTIONS="${ASAN_OPTIONS:-}" UBSAN_OPTIONS="${UBSAN_OPTIONS:-}" TSAN_OPTIONS="${TSAN_OPTIONS:-}"
shift || true
case "$kind" in
  address)
    build=build-asan
    # Longest first: binaries run two at a time, and a long one started last would run alone.
    # Each filter leaves out runs whose code another entry runs as well (said on its line); the
    # second run of each "...IsBitIdentical" test is the first one again.
    default_targets=(
      # Integration tests. integration_test (StaticTrackingTest) is left out: its run is
      # local_mapping_integration_test's SequentialMapping run (same sequence and options), its
      # missing-depth frame frame_faults_test's. So is dynamic_integration_test: its 60-second
      # scenario sweep is the yolo and dense-ghost runs' code, its bad choices are dynamic_test's
      # DynamicRunSetupTest.BadChoicesNameTheOption. Also left out: the soak, the real-camera
      # guard and the map-file runs (the map-file unit tests stay), and the demo with the network.
      # NoLoopWithoutRevisit: the first 200 frames of the Revisit run.
      loop_closing_integration_test:-*IsBitIdentical:*NoLoopWithoutRevisit
      yolo_integration_test
      # The frame faults: the reader detects each one in io_test (TumDatasetTest: corrupt,
      # truncated and empty files, missing depth, wrong sizes, timestamps), and a skipped frame
      # takes one path through the runner, which TruncatedPng runs end to end.
      frame_faults_test:-*CorruptPng*:*MissingDepthFiles*:*EmptyImageFile*:*FrameOfTheWrongSize*:*RepeatedAndBackwardTimestamps*
      benchmark_integration_test
      # RunsEachScenarioAndTheBaseline: the RunDemo of RunShorterThanTheRpeDelta, over three
      # scenarios and longer runs.
      demo_test:-*ModelAddsCutOutRows*:*RunsEachScenarioAndTheBaseline*
      local_mapping_integration_test:-*IsBitIdentical
      system_api_test
      options_registry_test
      realtime_integration_test
      run_stats_test
      # WithoutRelocalization: the relocalizing run with relocalization off.
      relocalization_integration_test:-*WithoutRelocalization*
      # drvslam ros2 end to end (the node is the sanitized CLI, in a child process) and its
      # conversions: loaned DDS samples and message buffers borrowed from C++ storage.
      ros2_node_test
      ros2_unit_test
      # Unit tests, all of them but two synthetic-camera renders: the handheld preset renders
      # blur and lens distortion too.
      synth_test:-*BlurLowersTheGradientEnergy*:*DistortedSequenceStatesItsCoefficients*
      dense_ghost_test
      # DenseOffWritesNoMap: a run with dense mapping off, as loop_closing_integration_test's.
      dense_run_test:-*DenseOffWritesNoMap
      dynamic_test dynamic_realtime_test synth_cli_test dense_test dense_mapper_test
      semantic_model_test loop_test relocalization_test eval_cli_test mapping_test
      local_bundle_adjustment_test loop_closing_test loop_closer_test io_test realtime_feeder_test
      semantic_test async_segmenter_test feature_test core_test core_threads_test eval_test
      match_test optim_test pose_graph_test
      rigid_transform_ransac_test tracking_test tracking_mapping_handoff_test map_file_test
      tracking_trajectory_smoother_test tracking_causal_pose_filter_test
      tracking_feature_budget_test tracking_keyframe_occlusion_test tracking_rolling_shutter_test
      occupancy_grid_test ros2_msgs_test synth_render_cache_test
      # The parsers of outside input on their fuzz corpora and the inputs that once found a bug.
      fuzz_regression_test
    )
    export ASAN_OPTIONS="detect_leaks=1:log_path=REPORTS/asan:${ASAN_OPTIONS:-}"
    # OpenCV's gPhoto2 camera backend off. cv::VideoCapture, handed a file no file backend reads
    # (the tests' "not a video" inputs), tries it, and libgphoto2's camera autodetection keeps
    # the libusb device lists it allocates (22 kB in 5,000 blocks per call; loop_test
    # TrainingImagesTest.BadInputsNameThePath, semantic_model_test through RunSegmentJob). With
    # fast_unwind_on_malloc=0 every frame from the allocation up to cv::VideoCapture::open is in
    # libusb, libgphoto2 or libopencv_videoio. An LSan suppression cannot name it: the default
    # unwinder stops at libusb (no frame pointers) and the other frame is in libgphoto2's
    # unloaded port plugin. No test opens a camera.
    export OPENCV_VIDEOIO_PRIORITY_GPHOTO2=0
    export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:log_path=REPORTS/ubsan:${UBSAN_OPTIONS:-}"
    ;;
  thread)
    build=build-tsan
    # Longest first: two run at a time. The threaded System runs render synthetic sequences that
    # have ground-truth masks, so each runs tracking with the ORB extractor's helper thread
    # (SideWorker, ORBextractor.threads 2), the segmentation thread, local mapping, loop closing
    # and the dense mapper together.
    default_targets=(
      # 301 frames around a room: a loop closed and a global BA while tracking goes on.
      loop_closing_integration_test:*Threaded*
      # 90 frames, every stage on: mapping, loop closing and dense beside tracking.
      local_mapping_integration_test:*Threaded*
      # A map reset while the other threads hold keyframes (Tracking.resetWhenLost).
      frame_faults_test:*Threaded*
      # --realtime: feeder thread, one-frame slot, segmentation dropping frames, keyframe waits.
      realtime_integration_test
      # The unit tests of the threads' hand-offs, each binary holding only those (tests/*/
      # CMakeLists.txt), so that this tree compiles nothing else of the unit tests.
      dense_mapper_test
      async_segmenter_test
      loop_closer_test
      realtime_feeder_test
      core_threads_test
      # The dynamic stage's flow helper (Dynamic.flowThread): same frames as without it, and a
      # frame abandoned with its flow job in flight.
      dynamic_realtime_test:DynamicFrontEndTest.FlowOnTheHelperThread*:DynamicFrontEndTest.AFrameAbandoned*
    )
    export TSAN_OPTIONS="second_deadlock_stack=1:log_path=REPORTS/tsan:${TSAN_OPTIONS:-}"
    # OpenCV's cv::parallel_for_ (the renderer's) runs on this system's OpenCV on uninstrumented
    # TBB, which orders its workers with atomics TSan does not see: the caller reading what a
    # worker wrote in a finished loop is reported as a race (170 reports per instrumented `synth`
    # run, each with a TBB worker). With one thread parallel_for_ runs its body on the caller,
    # so every access TSan checks is ordered by our own, instrumented, synchronization. Threaded
    # SLAM runs set OpenCV to one thread themselves (ApplyOpenCvThreadBudget).
    export OPENCV_FOR_THREADS_NUM=1
    # Without address randomization: GCC 12's TSan does not know the memory layout kernels with
    # more mmap randomization bits give ("unexpected memory mapping").
    run_prefix=(setarch "$(uname -m)" -R)
    ;;
  *)
    echo "usage: $0 address|thread [TEST_TARGET[:GTEST_FILTER]]..." >&2
    exit 2
    ;;
esac
# The integration tests render their synthetic sequences with `drvslam synth` first: with the
# release CLI when there is one, as rendering is not what these jobs test (synth_test and
# synth_cli_test render under ASan) and is slow instrumented: a 90-frame sequence took 11 s
# released and over 4 min under TSan; local_mapping_integration_test took 49 s under ASan
# rendering its own, 40 s with the release CLI's.
# The same release CLI rendered the same sequences for the release build's CTest run: its cache
# of rendered sequences (tests/integration/synth_render_cache.h) serves them here too.
if [ -x build/bin/drvslam ]; then
  export DRVSLAM_TEST_SYNTH_CLI="$root/build/bin/drvslam"
  export DRVSLAM_TEST_SYNTH_CACHE="${DRVSLAM_TEST_SYNTH_CACHE:-$root/build/test-synth-cache}"
fi
# Third-party false positives (uninstrumented OpenCV/TBB, libgomp, Ceres), one per line with a
# comment saying why the report is not ours: scripts/sanitizers/{lsan,tsan}.supp when needed.
for tool in lsan tsan; do
  if [ -s "scripts/sanitizers/$tool.supp" ]; then
    variable="${tool^^}_OPTIONS"
    export "$variable=suppressions=$root/scripts/sanitizers/$tool.supp:${!variable:-}"
  fi
done
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=("${default_targets[@]}")

# The release build's vocabulary when there is one (CI builds it first); otherwise this build
# trains its own.
release_vocabulary=build/share/drvslam/default_vocab.bin
train_vocabulary=ON
if [ -s "$release_vocabulary" ]; then
  train_vocabulary=OFF
  mkdir -p "$build/share/drvslam"
  cp "$release_vocabulary" "$build/share/drvslam/default_vocab.bin"
fi

# Ninja when installed (install-deps.sh installs it) and the folder is new: it schedules the whole
# graph at once; make also builds the one target below in parallel, only less evenly.
# The address tree is compiled by clang-16 (the fuzzers need it, and it compiles instrumented
# code in half GCC's time); the thread tree by the default compiler, GCC, whose TSan runs of
# these tests are the ones examined so far (scripts/sanitizers/tsan.supp). A folder keeps the
# compiler it was configured with.
compiler=()
# The orchestration code (the runner, the viewer, the evaluation, and in the address tree the
# CLI: cmake/DrvslamSanitizers.cmake) is compiled at -O0 in both trees, and in the address tree
# the test sources too (cmake/DrvslamModule.cmake says why); the modules the tests run for long
# (tracking, mapping, dense, rendering, the synthetic truth) keep -O1. In the thread tree the
# viewer, runner and evaluation batches took 40, 28 and 21 CPU-s at -O1.
test_optimization=-O1
unoptimized_targets="drvslam_runner;drvslam_viewer;drvslam_eval"
if [ "$kind" = address ]; then
  test_optimization=-O0
  unoptimized_targets="drvslam_cli;$unoptimized_targets"
fi
if [ ! -e "$build/CMakeCache.txt" ]; then
  if command -v ninja >/dev/null; then generator=(-G Ninja); fi
  if [ "$kind" = address ]; then
    if ! command -v clang++-16 >/dev/null; then
      echo "error: the address job builds with clang-16, which is missing:" \
        "run scripts/install-deps.sh" >&2
      exit 2
    fi
    compiler=(-DCMAKE_C_COMPILER=clang-16 -DCMAKE_CXX_COMPILER=clang++-16)
  fi
elif [ "$kind" = address ] && ! grep -q '^CMAKE_CXX_COMPILER:[A-Z]*=.*clang' "$build/CMakeCache.txt"; then
  # A folder configured before the address job moved to clang keeps GCC, which the fuzzers
  # cannot use.
  echo "error: $build/ was configured with another compiler than clang-16: remove it" \
    "(rm -rf $build) and run this job again" >&2
  exit 2
fi
# The address job's tests run the instrumented CLI (end-to-end runs, `drvslam ros2`); the thread
# job's only render their sequences with it, which the release CLI does (above), so that job
# builds no CLI (DRVSLAM_TESTS_WITHOUT_CLI: nor the ROS 2 node and apps/ only the CLI links).
build_targets=()
tests_without_cli=OFF
# The address tree also builds the libFuzzer targets (fuzz/): their instrumented modules are the
# ones these tests run, so one tree serves both. scripts/fuzz.sh runs them (.ci/run after this).
fuzzers=OFF
if [ "$kind" = address ]; then
  fuzzers=ON
  build_targets+=(drvslam_fuzzers)
fi
if [ "$kind" = thread ]; then
  if [ -z "${DRVSLAM_TEST_SYNTH_CLI:-}" ]; then
    echo "error: the thread job renders its sequences with the release CLI build/bin/drvslam," \
      "which is missing: run scripts/build.sh first" >&2
    exit 2
  fi
  tests_without_cli=ON
else
  build_targets+=(drvslam_cli)
fi
for entry in "${targets[@]}"; do build_targets+=("${entry%%:*}"); done
[ "$train_vocabulary" = ON ] && build_targets+=(drvslam_default_vocab)
# All of them as one target (drvslam_sanitizer_set): make takes targets named on one command
# line one after another.
cmake -S . -B "$build" ${generator[@]+"${generator[@]}"} ${compiler[@]+"${compiler[@]}"} \
  -DDRVSLAM_SANITIZE="$kind" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCMAKE_UNITY_BUILD=ON \
  -DDRVSLAM_TEST_OPTIMIZATION="$test_optimization" \
  -DDRVSLAM_UNOPTIMIZED_TARGETS="$unoptimized_targets" -DCMAKE_GTEST_DISCOVER_TESTS_DISCOVERY_MODE=PRE_TEST \
  -DDRVSLAM_BUILD_BENCH=OFF -DDRVSLAM_BUILD_PYTHON=OFF -DDRVSLAM_BUILD_FUZZERS="$fuzzers" \
  -DDRVSLAM_BUILD_DEFAULT_VOCABULARY="$train_vocabulary" -DDRVSLAM_TESTS_WITHOUT_CLI="$tests_without_cli" \
  -DDRVSLAM_SANITIZER_TARGETS="$(IFS=';'; echo "${build_targets[*]}")" >/dev/null

# CPU seconds (user + system) of this script's finished child processes so far, in cpu_seconds
# (`times` in this shell, not in a command substitution's): the wall times below depend on what
# else the machine runs, these less.
read_children_cpu() {
  local times_file="$build/.times"
  times >"$times_file"
  cpu_seconds=$(tail -n 1 "$times_file" | awk '{
    total = 0
    for (i = 1; i <= 2; i++) { split($i, part, /[ms]/); total += part[1] * 60 + part[2] }
    printf "%d", total
  }')
}
read_children_cpu
cpu_started=$cpu_seconds
started=$(date +%s)
cmake --build "$build" -j "$(nproc)" --target drvslam_sanitizer_set
read_children_cpu
cpu_built=$cpu_seconds
echo "sanitizers ($kind): build finished in $(($(date +%s) - started)) s" \
  "($((cpu_built - cpu_started)) CPU-s; load average $(cut -d' ' -f1-3 /proc/loadavg))"

# One binary: its output and its sanitizer reports in logs/<n>.*; a line when it ends.
logs="$build/sanitizer-logs"
rm -rf "$logs"
mkdir -p "$logs"
# True when the only report is LeakSanitizer's own stop-the-world tracer crashing at exit
# ("Tracer caught signal 11 ... LeakSanitizer has encountered a fatal error"): the leak check did
# not run, so nothing was found or cleared. A known, intermittent fault of the runtime
# (google/sanitizers#1353), seen once in CI after synth_test's 63 tests had all passed.
leak_checker_crashed() {
  local out="$1" reports="$2"
  grep -q 'LeakSanitizer has encountered a fatal error' "$out" "$reports"/* 2>/dev/null || return 1
  ! grep -q -E 'ERROR: (AddressSanitizer|LeakSanitizer): [a-z]|runtime error:' "$out" "$reports"/* 2>/dev/null
}
run_one() {
  local index="$1" entry="$2"
  local target="${entry%%:*}" filter="*"
  [[ "$entry" == *:* ]] && filter="${entry#*:}"
  local reports="$logs/$index.reports"
  local begun status attempt note=""
  begun=$(date +%s)
  # A second run only when the leak checker itself crashed; its verdict is the one given.
  for attempt in 1 2; do
    rm -rf "$reports"
    mkdir -p "$reports"
    status=0
    ASAN_OPTIONS="${ASAN_OPTIONS//REPORTS/$reports}" UBSAN_OPTIONS="${UBSAN_OPTIONS//REPORTS/$reports}" \
      TSAN_OPTIONS="${TSAN_OPTIONS//REPORTS/$reports}" \
      ${run_prefix[@]+"${run_prefix[@]}"} "$build/tests/$target" --gtest_filter="$filter" >"$logs/$index.out" 2>&1 || status=$?
    if [ "$attempt" -eq 1 ] && leak_checker_crashed "$logs/$index.out" "$reports"; then
      note=" (run twice: the leak checker crashed in the first run)"
      cp "$logs/$index.out" "$logs/$index.first.out"
      continue
    fi
    break
  done
  local verdict=ok
  if [ "$status" -ne 0 ]; then verdict="FAILED (exit status $status)"; fi
  if [ -n "$(ls -A "$reports")" ]; then verdict="FAILED (sanitizer reports)"; fi
  echo "sanitizers ($kind): $target --gtest_filter=$filter: $verdict$note in $(($(date +%s) - begun)) s"
  if [ "$verdict" != ok ]; then
    tail -n 40 "$logs/$index.out"
    cat "$reports"/* 2>/dev/null || true
    return 1
  fi
}

started=$(date +%s)
failed=0
index=0
running=0
for entry in "${targets[@]}"; do
  index=$((index + 1))
  run_one "$index" "$entry" &
  running=$((running + 1))
  if [ "$running" -ge "$(nproc)" ]; then
    wait -n || failed=1
    running=$((running - 1))
  fi
done
while [ "$running" -gt 0 ]; do
  wait -n || failed=1
  running=$((running - 1))
done
read_children_cpu
echo "sanitizers ($kind): tests finished in $(($(date +%s) - started)) s" \
  "($((cpu_seconds - cpu_built)) CPU-s; load average $(cut -d' ' -f1-3 /proc/loadavg))"
exit "$failed"
