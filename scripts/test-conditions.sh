#!/usr/bin/env bash
# Runs the whole test suite (scripts/test.sh) the ways a fresh machine can differ from the one
# a test was written on (project issue 28), and prints each condition's pass/fail counts and
# wall time:
#   one-core      pinned to one core (taskset -c 0: nproc, ctest -j and every thread see 1 core)
#   stress        beside `stress-ng --cpu 2` (two busy cores' worth of other work)
#   twice         twice in a row in the same build folder (leftovers of the first run)
#   fresh-clone   from a fresh `git clone` of this checkout's commit in a temporary folder, with
#                 ../shared beside it (a link to this checkout's ../shared)
# Exits 1 when any condition fails. Takes long: the suite runs five times and the fresh clone
# builds from scratch (over an hour on a 2-core machine).
#
# Usage: scripts/test-conditions.sh [CONDITION...]   (default: all four, in the order above)
# KEEP_CLONE=1 keeps the fresh clone's folder (its path is printed). Logs go to
# build/test-conditions/<condition>.log.
set -uo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
cd "$repo" || exit 2

conditions=("$@")
if [ ${#conditions[@]} -eq 0 ]; then
  conditions=(one-core stress twice fresh-clone)
fi
for condition in "${conditions[@]}"; do
  case "$condition" in
    one-core | stress | twice | fresh-clone) ;;
    *)
      echo "error: unknown condition '$condition' (one-core, stress, twice, fresh-clone)" >&2
      exit 2
      ;;
  esac
done

as_root() {
  if [ "$(id -u)" -eq 0 ]; then
    "$@"
  elif command -v sudo >/dev/null 2>&1; then
    sudo "$@"
  else
    echo "error: need root (or sudo) to run: $*" >&2
    return 2
  fi
}

# stress-ng for the "stress" condition, installed the way scripts/install-deps.sh installs
# packages (Debian's apt), only when that condition runs and it is missing.
need_stress_ng() {
  command -v stress-ng >/dev/null 2>&1 && return 0
  echo "test-conditions: installing stress-ng"
  export DEBIAN_FRONTEND=noninteractive
  as_root apt-get update -qq && as_root apt-get install -y -qq --no-install-recommends stress-ng
}

# Everything started here is stopped on exit, whatever ends the script.
stress_pid=""
clone_dir=""
# shellcheck disable=SC2317  # called by the trap
cleanup() {
  if [ -n "$stress_pid" ]; then
    kill "$stress_pid" 2>/dev/null
    wait "$stress_pid" 2>/dev/null
  fi
  if [ -n "$clone_dir" ] && [ "${KEEP_CLONE:-0}" = "0" ]; then
    rm -rf "$clone_dir"
  fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

logs="$repo/build/test-conditions"
mkdir -p "$logs"
results=()
failed=0

# run_suite NAME DIR COMMAND...: runs the suite's command in DIR, logs it, and records the
# counts from CTest's summary ("N% tests passed, F tests failed out of T").
run_suite() {
  local name="$1" dir="$2"
  shift 2
  local log="$logs/$name.log"
  echo "test-conditions: $name: $* (in $dir; log $log)"
  local start end status
  start=$(date +%s)
  (cd "$dir" && "$@") >"$log" 2>&1
  status=$?
  end=$(date +%s)
  local summary passed=0 failures=0 total=0 verdict=pass
  summary=$(grep -E '[0-9]+% tests passed, [0-9]+ tests? failed out of [0-9]+' "$log" | tail -1)
  if [ -n "$summary" ]; then
    failures=$(sed -E 's/.* ([0-9]+) tests? failed out of.*/\1/' <<<"$summary")
    total=$(sed -E 's/.*out of ([0-9]+).*/\1/' <<<"$summary")
    passed=$((total - failures))
  fi
  if [ "$status" -ne 0 ] || [ -z "$summary" ] || [ "$failures" -ne 0 ]; then
    verdict=FAIL
    failed=1
    [ -z "$summary" ] && verdict="FAIL (no test summary: the build or setup failed)"
  fi
  results+=("$(printf '%-14s %4d passed %4d failed of %4d  %6ds  %s' \
    "$name" "$passed" "$failures" "$total" "$((end - start))" "$verdict")")
  echo "test-conditions: ${results[-1]}"
  if [ "$verdict" != pass ]; then
    grep -E '^\s+[0-9]+ - .*\((Failed|Timeout|SEGFAULT|Subprocess aborted|Not Run)' "$log" |
      sed 's/^/    /'
  fi
}

for condition in "${conditions[@]}"; do
  case "$condition" in
    one-core)
      run_suite one-core "$repo" taskset -c 0 bash scripts/test.sh
      ;;
    stress)
      if ! need_stress_ng; then
        results+=("$(printf '%-14s %s' stress 'FAIL (stress-ng could not be installed)')")
        failed=1
        continue
      fi
      # --timeout: stress-ng ends by itself even if this script is killed without its trap.
      stress-ng --cpu 2 --timeout 4h --quiet &
      stress_pid=$!
      run_suite stress "$repo" bash scripts/test.sh
      kill "$stress_pid" 2>/dev/null
      wait "$stress_pid" 2>/dev/null
      stress_pid=""
      ;;
    twice)
      run_suite twice-1 "$repo" bash scripts/test.sh
      run_suite twice-2 "$repo" bash scripts/test.sh
      ;;
    fresh-clone)
      clone_dir=$(mktemp -d "${TMPDIR:-/tmp}/drvslam-fresh-clone.XXXXXX")
      commit=$(git -C "$repo" rev-parse HEAD)
      if [ -n "$(git -C "$repo" status --porcelain --untracked-files=no)" ]; then
        echo "test-conditions: note: uncommitted changes are not in the clone (it tests $commit)"
      fi
      if ! git clone -q "$repo" "$clone_dir/drvslam" ||
        ! git -C "$clone_dir/drvslam" checkout -q "$commit"; then
        results+=("$(printf '%-14s %s' fresh-clone "FAIL (git clone of $repo failed)")")
        failed=1
        continue
      fi
      # The models and data a checkout finds at ../shared (DRVSLAM_SHARED_DIR's default).
      if [ -e "$repo/../shared" ]; then
        ln -s "$(cd "$repo/../shared" && pwd -P)" "$clone_dir/shared"
      else
        echo "test-conditions: note: no $repo/../shared: the clone has none either"
      fi
      run_suite fresh-clone "$clone_dir/drvslam" bash scripts/test.sh
      [ "${KEEP_CLONE:-0}" != "0" ] && echo "test-conditions: kept $clone_dir"
      ;;
  esac
done

echo
echo "test-conditions: results (scripts/test.sh under each condition)"
printf '  %s\n' "${results[@]}"
exit "$failed"
