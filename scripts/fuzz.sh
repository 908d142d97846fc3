#!/usr/bin/env bash
# Fuzzes the parsers of outside input with the libFuzzer targets of fuzz/ (docs/getting-started.md
# #fuzzing): ROS 2 image and camera-info messages, map files, settings files, TUM lists and
# trajectories, vocabularies, ONNX metadata. The targets come from a clang ASan+UBSan tree
# configured with -DDRVSLAM_BUILD_FUZZERS=ON (ninja -C build-asan drvslam_fuzzers).
#
#   scripts/fuzz.sh [--build DIR] [--runs N] [TARGET...]
#       CI: each target runs N inputs (default 2000; settings 300, as each of its inputs goes
#       through FileStorage and every option loader: 5 inputs/s under ASan against 100-2000 for
#       the others) starting from its seeds and its regression inputs (fuzz/corpus/<target>,
#       fuzz/regressions/<target>), two targets at a time: about 2 minutes of CPU in all.
#   scripts/fuzz.sh [--build DIR] --seconds S [--jobs J] [TARGET...]
#       A campaign: each target for S seconds (-max_total_time), one at a time (J at a time with
#       --jobs), then a table of executions, coverage (cov: edges) and features (ft).
# TARGET: ros2_image map_file settings tum_text vocabulary onnx_metadata (default: every one the
# build has). Every run has -rss_limit_mb=1024 -malloc_limit_mb=512 -timeout=30 and the target's
# dictionary (fuzz/dict/<target>.dict), so an unbounded allocation, a leak, a hang or a crash is a
# finding. The time limit is wall time: 30 s, as a campaign beside builds (load 10 on 2 cores)
# stopped a settings input at 12 s that takes 0.6 CPU-s. The corpora are copied to a scratch
# folder (fuzz-out/ in the build folder, with each target's log); new inputs found stay there,
# git's files are not changed.
# Exit status 1 when a target found something: the input is printed (fuzz-out/<target>/crash-*
# etc.); replay it with `BUILD/bin/<target>_fuzzer FILE`, fix the parser, and keep the input in
# fuzz/regressions/<target>/ (fuzz_regression_test replays it in every build).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)

build=build-asan
runs=
seconds=
jobs=
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$2"; shift 2 ;;
    --runs) runs="$2"; shift 2 ;;
    --seconds) seconds="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    -h|--help) sed -n '2,24p' "$0"; exit 0 ;;
    -*) echo "fuzz.sh: unknown option $1" >&2; exit 2 ;;
    *) targets+=("$1"); shift ;;
  esac
done
# An absolute --build works as a relative one: the fuzzers run from "$root/$build" below.
build=$(realpath -m --relative-to="$root" "$build")
[ -n "$jobs" ] || { [ -n "$seconds" ] && jobs=1 || jobs=2; }

if [ ${#targets[@]} -eq 0 ]; then
  for corpus in fuzz/corpus/*/; do
    name=$(basename "$corpus")
    [ -x "$build/bin/${name}_fuzzer" ] && targets+=("$name")
  done
fi
if [ ${#targets[@]} -eq 0 ]; then
  echo "fuzz.sh: no fuzz targets in $build/bin; configure a clang tree with" \
       "-DDRVSLAM_SANITIZE=address -DDRVSLAM_BUILD_FUZZERS=ON and build drvslam_fuzzers" >&2
  exit 2
fi
for name in "${targets[@]}"; do
  if [ ! -x "$build/bin/${name}_fuzzer" ]; then
    echo "fuzz.sh: $build/bin/${name}_fuzzer is not built" >&2
    exit 2
  fi
done

out="$root/$build/fuzz-out"
rm -rf "$out"
mkdir -p "$out"
# Leaks are findings; undefined behaviour stops the program (as in scripts/sanitizers.sh).
export ASAN_OPTIONS="detect_leaks=1:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:${UBSAN_OPTIONS:-}"

# One target: its corpus copied, then libFuzzer in that folder; the log beside it.
fuzz_one() {
  local name="$1" dir="$out/$1"
  mkdir -p "$dir/corpus" "$dir/artifacts"
  cp fuzz/corpus/"$name"/* "$dir/corpus/"
  if [ -d "fuzz/regressions/$name" ]; then cp fuzz/regressions/"$name"/* "$dir/corpus/" 2>/dev/null || true; fi
  local count="$runs"
  [ -n "$count" ] || { [ "$name" = settings ] && count=300 || count=2000; }
  local limit=(-runs="$count")
  [ -n "$seconds" ] && limit=(-max_total_time="$seconds")
  local dict=()
  [ -f "fuzz/dict/$name.dict" ] && dict=(-dict="$root/fuzz/dict/$name.dict")
  local status=0
  "$root/$build/bin/${name}_fuzzer" "$dir/corpus" "${limit[@]}" "${dict[@]}" \
      -rss_limit_mb=1024 -malloc_limit_mb=512 -timeout=30 -print_final_stats=1 \
      -artifact_prefix="$dir/artifacts/" > "$dir/log.txt" 2>&1 || status=$?
  echo "$status" > "$dir/status"
}
export -f fuzz_one
export out runs seconds build root

start=$(date +%s)
printf '%s\n' "${targets[@]}" | xargs -P "$jobs" -I{} bash -c 'fuzz_one "$@"' _ {}
elapsed=$(( $(date +%s) - start ))

failed=0
printf '%-14s %8s %10s %8s %8s  %s\n' target status executions cov ft log
for name in "${targets[@]}"; do
  dir="$out/$name"
  # A fuzzer that never wrote its status (killed, or not started) failed.
  status=$(cat "$dir/status" 2>/dev/null || echo "none")
  # libFuzzer's last line: "#N DONE cov: X ft: Y corp: ..."; the stats: "stat::number_of_executed_units: N".
  done_line=$(grep -E '^#[0-9]+[[:space:]]+DONE' "$dir/log.txt" | tail -n 1 || true)
  executions=$(grep -oE 'stat::number_of_executed_units: [0-9]+' "$dir/log.txt" | awk '{print $2}' | tail -n 1 || true)
  cov=$(sed -nE 's/.* cov: ([0-9]+).*/\1/p' <<< "$done_line")
  ft=$(sed -nE 's/.* ft: ([0-9]+).*/\1/p' <<< "$done_line")
  printf '%-14s %8s %10s %8s %8s  %s\n' "$name" "$status" "${executions:--}" "${cov:--}" "${ft:--}" \
    "${dir#"$root/"}/log.txt"
  # libFuzzer also writes inputs that took over 10 s (slow-unit-*). That is wall time, which a
  # loaded machine stretches: a note, not a finding; -timeout=30 makes a hang a finding.
  findings=$(find "$dir/artifacts" -type f ! -name 'slow-unit-*' | sort)
  slow=$(find "$dir/artifacts" -type f -name 'slow-unit-*' | sort)
  if [ -n "$slow" ]; then
    echo "  $name: $(wc -l <<< "$slow") inputs took over 10 s of wall time (not a finding;" \
         "replay one alone to see its time):" >&2
    for input in $slow; do echo "    ${input#"$root/"}" >&2; done
  fi
  if [ "$status" != 0 ] || [ -n "$findings" ]; then
    failed=1
    echo "  $name found a problem (exit status $status):" >&2
    grep -E 'ERROR: (AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer|libFuzzer)|runtime error:|SUMMARY:' \
      "$dir/log.txt" | head -n 5 | sed 's/^/    /' >&2 || true
    for finding in $findings; do echo "  input: ${finding#"$root/"}" >&2; done
  fi
done
echo "fuzz.sh: ${#targets[@]} targets in ${elapsed} s (logs and grown corpora in ${out#"$root/"})"
exit "$failed"
