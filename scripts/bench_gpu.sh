#!/usr/bin/env bash
# On a GPU machine, with binaries in carry/: the full Table-1 benchmark (all scenes, movements,
# sp and dp) at 1500x1000 with the resolution scale study, its plots, and the timelines of one
# walkthrough frame. Writes to $OUT (or out/bench): results.json, results.md, results.csv,
# frame_time.png, speedup.png, timeline.log.
set -uo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-out/bench}"
mkdir -p "$out"
./carry/gvdp bench --backend cuda --scale --out "$out/results.json" --csv "$out/results.csv" \
  --markdown "$out/results.md" "$@"
python3 scripts/plot_bench.py "$out/results.json" "$out"
for sched in sp dp; do
  ./carry/gvdp timeline --backend cuda --scheduler "$sched" --scene perlin --frame 12 \
    --out "/tmp/timeline_$sched.png" | tee -a "$out/timeline.log"
done
