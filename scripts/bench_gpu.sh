#!/usr/bin/env bash
# On a GPU machine, with binaries in carry/: the full Table-1 benchmark (all scenes, movements,
# sp, dp, pt and graph) at 1500x1000, its plots, the speed-ups cell by cell, 1000 pt and graph
# frames at 320x200 (unfinished pixels), the timelines of walkthrough frame 12 (sp, dp, pt;
# perlin and random-spheres) and the timeline's overhead on pt. Extra arguments go to the
# benchmark (--scale adds dp's resolution study). Writes to $OUT (or out/bench): results.json,
# results.md, results.csv, frame_time.png, speedup.png, summary.txt (speed-ups, unfinished
# pixels, timeline statistics and overhead), timeline_pt_perlin.png, timeline_pt_random-spheres.png.
set -uo pipefail
# A GPU hang ends its run in a minute with a line naming where it waited (base/watchdog.h),
# instead of taking the rest of the call.
export GVDP_WATCHDOG_S="${GVDP_WATCHDOG_S:-60}"
cd "$(dirname "$0")/.."
out="${OUT:-out/bench}"
mkdir -p "$out"
./carry/gvdp bench --backend cuda --schedulers sp,dp,pt,graph --out "$out/results.json" \
  --csv "$out/results.csv" --markdown "$out/results.md" "$@"
python3 scripts/plot_bench.py "$out/results.json" "$out"
python3 scripts/pt_vs_dp.py "$out/results.json" | tee "$out/summary.txt"
./carry/gvdp bench --backend cuda --schedulers pt,graph --frames 40 --warmup 0 --width 320 \
  --height 200 --out /tmp/small.json >/dev/null
python3 -c "
import json
r = json.load(open('/tmp/small.json'))
for k in ('pt', 'graph'):
    cells = [c for c in r['cells'] if c['scheduler'] == k]
    print('%s 320x200: %d frames, %d unfinished pixels' % (k, sum(len(c['frame_ms']) for c in cells),
          sum(c['unfinished_pixels'] for c in cells)))
" | tee -a "$out/summary.txt"
for sched in sp dp pt; do
  for scene in perlin random-spheres; do
    ./carry/gvdp timeline --backend cuda --scheduler "$sched" --scene "$scene" --frame 12 \
      --out "/tmp/timeline_${sched}_$scene.png" | tee -a "$out/summary.txt"
  done
done
cp /tmp/timeline_pt_perlin.png /tmp/timeline_pt_random-spheres.png "$out/"
for mode in off on; do
  flag=""
  [ "$mode" = on ] && flag="--timeline /tmp/tl_pt"
  ./carry/gvdp render --backend cuda --scheduler pt --scene perlin --frames 24 --out /tmp/ov_pt \
    $flag >/dev/null
  python3 -c "
import json, statistics
f = json.load(open('/tmp/ov_pt/stats.json'))['frames'][1:]
print('timeline overhead, pt perlin 1500x1000, timeline $mode: median %.2f ms' % statistics.median(x['ms'] for x in f))
" | tee -a "$out/summary.txt"
done
