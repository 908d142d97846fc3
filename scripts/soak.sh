#!/usr/bin/env bash
# Soak: a long synthetic circuit (loop closures every turn) through `drvslam run`, with the
# resident memory (VmRSS) of the run sampled every 10 s (the run reports no frame count while it
# runs; at 2 cores 1,000 frames take roughly 30-60 s, so several samples per 1,000 frames).
#   scripts/soak.sh [FRAMES=20000] [OUT=/tmp/drvslam_soak] [extra drvslam run flags...]
# Writes OUT/rss.tsv (seconds, rss_kib) and OUT/run/ (trajectories, stats.json with frames,
# keyframes and map_points). The synthetic sequence is made once and reused (OUT/seq_FRAMES).
set -euo pipefail
cd "$(dirname "$0")/.."
frames="${1:-20000}"
out="${2:-/tmp/drvslam_soak}"
shift $(( $# > 2 ? 2 : $# ))
cli=build/bin/drvslam
[ -x "$cli" ] || { echo "build drvslam_cli first" >&2; exit 2; }
mkdir -p "$out"
seq_dir="$out/seq_$frames"
if [ ! -f "$seq_dir/associations.txt" ]; then
  "$cli" --log-level warn synth --scenario static_circuit --frames "$frames" --out "$seq_dir"
fi
"$cli" --log-level warn run --dataset "$seq_dir" --out "$out/run" --dense off "$@" &
pid=$!
printf 'seconds\trss_kib\n' > "$out/rss.tsv"
start=$(date +%s)
while kill -0 "$pid" 2>/dev/null; do
  rss=$(awk '/VmRSS/ {print $2}' "/proc/$pid/status" 2>/dev/null || true)
  [ -n "$rss" ] && printf '%s\t%s\n' "$(( $(date +%s) - start ))" "$rss" >> "$out/rss.tsv"
  sleep 10
done
wait "$pid"
echo "RSS samples: $out/rss.tsv; run: $out/run/stats.json"
