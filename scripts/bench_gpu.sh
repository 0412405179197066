#!/usr/bin/env bash
# On a GPU machine, with binaries in carry/: the full Table-1 benchmark (all scenes, movements,
# sp, dp, pt and graph) at 1500x1000 with the resolution scale study, its plots, pt's speed-up
# over dp cell by cell, 1000 pt and graph frames at 320x200 (unfinished pixels), and the
# timelines of one walkthrough frame. Writes to $OUT (or out/bench): results.json, results.md,
# results.csv, frame_time.png, speedup.png, pt_vs_dp.txt, timeline.log, timeline_pt_*.png.
set -uo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-out/bench}"
mkdir -p "$out"
./carry/gvdp bench --backend cuda --scale --schedulers sp,dp,pt,graph --out "$out/results.json" \
  --csv "$out/results.csv" --markdown "$out/results.md" "$@"
python3 scripts/plot_bench.py "$out/results.json" "$out"
python3 scripts/pt_vs_dp.py "$out/results.json" | tee "$out/pt_vs_dp.txt"
./carry/gvdp bench --backend cuda --schedulers pt,graph --frames 40 --warmup 0 --width 320 \
  --height 200 --out /tmp/small.json >/dev/null
python3 -c "
import json
r = json.load(open('/tmp/small.json'))
for k in ('pt', 'graph'):
    cells = [c for c in r['cells'] if c['scheduler'] == k]
    print('%s 320x200: %d frames, %d unfinished pixels' % (k, sum(len(c['frame_ms']) for c in cells),
          sum(c['unfinished_pixels'] for c in cells)))
" | tee -a "$out/pt_vs_dp.txt"
for sched in sp dp pt; do
  for scene in perlin random-spheres; do
    ./carry/gvdp timeline --backend cuda --scheduler "$sched" --scene "$scene" --frame 12 \
      --out "/tmp/timeline_${sched}_$scene.png" | tee -a "$out/timeline.log"
  done
done
cp /tmp/timeline_pt_perlin.png /tmp/timeline_pt_random-spheres.png "$out/"
