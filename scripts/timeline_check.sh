#!/usr/bin/env bash
# On a GPU machine, with binaries in carry/: timelines of the same walkthrough frame for sp, dp and
# pt (PNG + summary), and the profiler's overhead (the same 24 frames with and without it).
# Writes to $OUT (or out/timeline_check). Usage: scripts/timeline_check.sh [scene] [frame]
set -uo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-out/timeline_check}"
mkdir -p "$out"
scene="${1:-perlin}"
frame="${2:-12}"
for sched in sp dp pt; do
  ./carry/gvdp timeline --backend cuda --scheduler "$sched" --scene "$scene" --frame "$frame" \
    --width 1500 --height 1000 --out "$out/timeline_${sched}_${scene}.png" | tee -a "$out/timeline.log"
done
for sched in sp dp pt; do
  for mode in off on; do
    flag=""
    [ "$mode" = on ] && flag="--timeline /tmp/tl_$sched"
    ./carry/gvdp render --backend cuda --scheduler "$sched" --scene "$scene" --frames 24 \
      --width 1500 --height 1000 --out "/tmp/ov_${sched}_$mode" $flag >"/tmp/ov_${sched}_$mode.log"
    python3 -c "
import json,statistics
f=json.load(open('/tmp/ov_${sched}_$mode/stats.json'))['frames'][1:]
print('overhead $sched timeline $mode: median %.2f ms, mean %.2f ms' % (statistics.median(x['ms'] for x in f), statistics.mean(x['ms'] for x in f)))
" | tee -a "$out/timeline.log"
  done
done
