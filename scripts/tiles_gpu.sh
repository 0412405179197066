#!/usr/bin/env bash
# Tiled frames on a GPU (issue 16), with binaries carried in carry/ (gvdp, gvdp_tests,
# gvdp_quadtree_bench from preset default):
#   1. the tiles', degraded frames' and quadtree's tests (GPU ones included);
#   2. the quadtree subdivision bench (every method, levels per pass 1..8);
#   3. a large still: perlin at SIZE x SIZE with a 512 MB pool, peak device memory sampled by
#      nvidia-smi every 100 ms;
#   4. --tiles auto against --tiles off on frames that fit (perlin walkthrough, 1500x1000);
#   5. frames that overflow the pool (forest backward, 1500x1000, 2000 bricks), tiles planned by
#      the importance pre-pass against quadrants alone (--tile-plan on / off), sp and pt.
# Writes to $OUT (or out/tiles_gpu): tests.log, quadtree.json, quadtree.txt, still.log,
# memory.csv, fit_auto.log, fit_off.log, plan_<scheduler>_<on|off>.log and .json.
# Usage: scripts/tiles_gpu.sh [SIZE] [steps]   (default 16384, "tests bench still fit plan")
set -uo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-out/tiles_gpu}"
mkdir -p "$out"
size="${1:-16384}"
steps="${2:-tests bench still fit plan}"
step() { [[ " $steps " == *" $1 "* ]]; }
export GVDP_BIN="$PWD/carry/gvdp"
export LD_LIBRARY_PATH="$PWD/carry/lib:${LD_LIBRARY_PATH:-}"
status=0
nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader

if step tests; then
echo "== tests"
./carry/gvdp_tests --gtest_brief=1 --gtest_filter='Tile*:Degraded*:Quadtree*:*TinyPool*:Importance*' \
  >"$out/tests.log" 2>&1 || status=1
grep -E "^\[  (FAILED|PASSED|SKIPPED) |^\[==========\]|measure|Failure|Expected|Which is|frame [0-9]" "$out/tests.log" | tail -n 40

fi
if step bench; then
echo "== quadtree bench"
./carry/gvdp_quadtree_bench --json "$out/quadtree.json" >"$out/quadtree.txt" 2>&1 || status=1
tail -n 60 "$out/quadtree.txt"

fi
if step still; then
echo "== still ${size}x${size}, perlin, pool 512 MB"
nvidia-smi --query-gpu=memory.used --format=csv,noheader,nounits -lms 100 >"$out/memory.csv" &
smi=$!
base=$(nvidia-smi --query-gpu=memory.used --format=csv,noheader,nounits)
start=$(date +%s%N)
./carry/gvdp render --backend cuda --scene perlin --width "$size" --height "$size" --frames 1 \
  --pool-mb 512 --out /tmp/still >"$out/still.log" 2>&1 || status=1
end=$(date +%s%N)
kill $smi
tail -n 6 "$out/still.log"
echo "wall $(( (end - start) / 1000000 )) ms (render and PNG); device memory used before ${base} MiB, peak $(sort -n "$out/memory.csv" | tail -n 1) MiB"
ls -la /tmp/still/frame_0000.png

fi
if step fit; then
echo "== frames that fit: --tiles auto and off, perlin walkthrough 1500x1000, 60 frames, twice"
for run in 1 2; do
  for mode in auto off; do
    ./carry/gvdp render --backend cuda --scene perlin --frames 60 --tiles $mode \
      --out /tmp/fit_$mode >"$out/fit_${mode}_$run.log" 2>&1 || status=1
    echo "$mode run $run: $(grep -c 'split on' "$out/fit_${mode}_$run.log") tiled frames; $(tail -n 1 "$out/fit_${mode}_$run.log")"
  done
done
fi
if step plan; then
echo "== frames that overflow: forest backward 1500x1000, pool 2000 bricks, 3 frames, plans / quadrants"
for sched in sp pt; do
  for plan in on off; do
    ./carry/gvdp render --backend cuda --scheduler $sched --scene forest --movement backward \
      --frames 3 --pool-bricks 2000 --tile-plan $plan --out /tmp/plan_${sched}_${plan} \
      >"$out/plan_${sched}_$plan.log" 2>&1 || status=1
    cp /tmp/plan_${sched}_${plan}/stats.json "$out/plan_${sched}_$plan.json" 2>/dev/null
    echo "$sched plan $plan:"; grep -E "^frame|tiles [0-9]+ " "$out/plan_${sched}_$plan.log"
  done
done
fi
echo "tiles_gpu: $([ $status -eq 0 ] && echo "all passed" || echo FAILED)"
exit $status
