#!/usr/bin/env bash
# Soak: a long synthetic circuit (static_circuit: the camera circles the table, one lap every
# 360 frames, so loops close lap after lap) through `drvslam run`, threaded. Every frame's map
# size and resident memory go to OUT/frames.tsv (`drvslam run --frame-log`); OUT/soak.md is the
# table every 1,000 frames: frames, keyframes, map points, RSS.
#   scripts/soak.sh [FRAMES=20000] [OUT=/tmp/drvslam_soak] [extra drvslam run flags...]
# Environment: DRVSLAM (the CLI, default build/bin/drvslam), SOAK_SIZE (WIDTHxHEIGHT of the
# sequence, default 320x240: 20,000 frames then take about 3.5 GB of PNGs instead of 14 GB).
# Dense mapping is off unless the extra flags say `--dense on`. The sequence is made once and
# reused (OUT/seq_FRAMES_SIZE).
set -euo pipefail
cd "$(dirname "$0")/.."
frames="${1:-20000}"
out="${2:-/tmp/drvslam_soak}"
shift $(($# > 2 ? 2 : $#))
cli="${DRVSLAM:-build/bin/drvslam}"
size="${SOAK_SIZE:-320x240}"
[ -x "$cli" ] || { echo "build drvslam_cli first (or set DRVSLAM)" >&2; exit 2; }
[[ "$size" =~ ^([0-9]+)x([0-9]+)$ ]] || { echo "SOAK_SIZE=$size: expected WIDTHxHEIGHT" >&2; exit 2; }
mkdir -p "$out"
seq_dir="$out/seq_${frames}_$size"
if [ ! -f "$seq_dir/associations.txt" ]; then
  "$cli" --log-level warn synth --scenario static_circuit --frames "$frames" \
    --width "${BASH_REMATCH[1]}" --height "${BASH_REMATCH[2]}" --out "$seq_dir"
fi
dense=(--dense off)
[[ " $* " == *" --dense "* ]] && dense=()
"$cli" --log-level info run --dataset "$seq_dir" --out "$out/run" "${dense[@]}" \
  --frame-log "$out/frames.tsv" "$@" > "$out/run.log" 2>&1
{
  echo "| frames | keyframes | map points | RSS MiB |"
  echo "|---:|---:|---:|---:|"
  awk -F'\t' 'NR > 1 && (($1 + 1) % 1000 == 0) {
      printf "| %d | %d | %d | %.1f |\n", $1 + 1, $6, $7, $8 / 1024 }' "$out/frames.tsv"
  echo
  echo "loop corrections: $(grep -c 'loop closed' "$out/run.log" || true)," \
    "global BAs: $(grep -c 'global bundle adjustment:' "$out/run.log" || true)"
} > "$out/soak.md"
cat "$out/soak.md"
echo "per frame: $out/frames.tsv; run: $out/run/stats.json, $out/run.log"
