#!/usr/bin/env bash
# Soak: a long synthetic circuit through `drvslam run`. One lap of static_circuit (the camera
# circles the table, one turn every 12 s = 360 frames at 30 Hz, back at its start) is rendered
# once; the sequence replays it lap after lap: its rgb.txt, depth.txt, associations.txt and
# groundtruth.txt list the lap's files again and again with timestamps that keep increasing
# (the images are symbolic links to the lap's folders, not copies), so loops close on every lap
# and 20,000 frames take 90 MB of disk instead of 3.5 GB. Every frame's map size and resident
# memory go to OUT/frames.tsv (`drvslam run --frame-log`); OUT/soak.md is the table every
# 1,000 frames (frames, keyframes, map points, RSS, loop corrections so far) and the memory a
# frame costs after warm-up beyond the map's growth (scripts/soak_table.py). Replayed laps are
# the same images, so after about two laps (loop corrections on laps 1-2) the map holds still:
# no new keyframes, hence no later loop closures; the rest of the run measures what a tracked
# frame costs. soak_integration_test covers a growing map (5 rendered laps).
#   scripts/soak.sh [FRAMES=20000] [OUT=/tmp/drvslam_soak] [extra drvslam run flags...]
# e.g. scripts/soak.sh 20000 /tmp/soak_seq --sequential
# Environment: DRVSLAM (the CLI, default build/bin/drvslam; it needs --frame-log), SYNTH_CLI
# (the CLI that renders the lap, default DRVSLAM), SOAK_SIZE (WIDTHxHEIGHT, default 320x240),
# SOAK_SEED (default 3), SOAK_WARMUP (frames before the memory fit, default 2000).
# Dense mapping is off unless the extra flags say `--dense on`. There are no masks in the
# replayed sequence, so the segmenter is `none` unless the flags choose one (e.g. yolo).
set -euo pipefail
cd "$(dirname "$0")/.."
frames="${1:-20000}"
out="${2:-/tmp/drvslam_soak}"
shift $(($# > 2 ? 2 : $#))
cli="${DRVSLAM:-build/bin/drvslam}"
synth_cli="${SYNTH_CLI:-$cli}"
size="${SOAK_SIZE:-320x240}"
seed="${SOAK_SEED:-3}"
warm_up="${SOAK_WARMUP:-2000}"
readonly lap_frames=360 lap_seconds=12
[ -x "$cli" ] || { echo "build drvslam_cli first (or set DRVSLAM)" >&2; exit 2; }
[[ "$size" =~ ^([0-9]+)x([0-9]+)$ ]] || { echo "SOAK_SIZE=$size: expected WIDTHxHEIGHT" >&2; exit 2; }
width="${BASH_REMATCH[1]}" height="${BASH_REMATCH[2]}"
[[ "$frames" =~ ^[1-9][0-9]*$ ]] || { echo "FRAMES=$frames: expected a positive number" >&2; exit 2; }
mkdir -p "$out"
out="$(cd "$out" && pwd)"

lap_dir="$out/lap_${size}_seed$seed"
if [ ! -f "$lap_dir/associations.txt" ]; then
  "$synth_cli" --log-level warn synth --scenario static_circuit --frames "$lap_frames" \
    --seed "$seed" --width "$width" --height "$height" --out "$lap_dir"
fi

# Lap k replays the lap's stamps shifted by k * 12 s; entries past FRAMES are left out.
seq_dir="$out/replay_${frames}_${size}_seed$seed"
rm -rf "$seq_dir"
mkdir -p "$seq_dir"
ln -s "../$(basename "$lap_dir")/rgb" "$seq_dir/rgb"
ln -s "../$(basename "$lap_dir")/depth" "$seq_dir/depth"
cp "$lap_dir/settings.yaml" "$seq_dir/settings.yaml"
laps=$(((frames + lap_frames - 1) / lap_frames))
replay_list() {  # FILE STAMP_COLUMNS: the lap's data lines, repeated, stamps shifted
  awk -v laps="$laps" -v limit="$frames" -v period="$lap_seconds" -v cols="$2" '
    /^#/ { next }
    { line[n++] = $0 }
    END {
      count = 0
      for (k = 0; k < laps; ++k)
        for (i = 0; i < n && (limit == 0 || count < limit); ++i) {
          nf = split(line[i], f, " ")
          text = ""
          for (j = 1; j <= nf; ++j) {
            v = (index(" " cols " ", " " j " ") > 0) ? sprintf("%.6f", f[j] + k * period) : f[j]
            text = text (j > 1 ? " " : "") v
          }
          print text
          ++count
        }
    }' "$1"
}
replay_list "$lap_dir/associations.txt" "1 3" > "$seq_dir/associations.txt"
replay_list "$lap_dir/rgb.txt" "1" > "$seq_dir/rgb.txt"
replay_list "$lap_dir/depth.txt" "1" > "$seq_dir/depth.txt"
# Ground truth has one pose per frame: the same limit (replayed frames see the same poses).
replay_list "$lap_dir/groundtruth.txt" "1" > "$seq_dir/groundtruth.txt"

dense=(--dense off)
[[ " $* " == *" --dense "* ]] && dense=()
start=$(date +%s)
"$cli" --log-level info run --dataset "$seq_dir" --out "$out/run" "${dense[@]}" \
  --frame-log "$out/frames.tsv" "$@" > "$out/run.log" 2>&1
echo "run: $(($(date +%s) - start)) s wall ($*)" > "$out/wall.txt"
python3 scripts/soak_table.py "$out/frames.tsv" "$out/run.log" --warm-up "$warm_up" > "$out/soak.md"
cat "$out/soak.md"
echo "per frame: $out/frames.tsv; run: $out/run/stats.json, $out/run.log; $(cat "$out/wall.txt")"
