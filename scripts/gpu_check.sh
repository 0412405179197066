#!/usr/bin/env bash
# On a machine with a GPU, with the binaries built elsewhere and carried in carry/: every test
# (GPU ones included), compute-sanitizer memcheck and racecheck on a short run per scheduler (the
# racecheck of all but dp on carry/nocdp/gvdp, preset nocdp), then a 1500x1000 walkthrough of
# each scene per scheduler. Writes to $OUT (or out/gpu_check): device.txt,
# tests.log, sanitizer.log, renders.log and montage_<scheduler>.png (frame 0 of every scene).
# Usage: scripts/gpu_check.sh [frames] [schedulers...]
set -uo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-out/gpu_check}"
mkdir -p "$out"
frames="${1:-8}"
shift || true
schedulers=("${@:-sp}")
scenes=(perlin fbm forest random-spheres aligned-spheres)
export GVDP_BIN="$PWD/carry/gvdp"
nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader | tee "$out/device.txt"
status=0
./carry/gvdp_tests 2>&1 | tee "$out/tests.log" | grep -E "^\[  (FAILED|PASSED|SKIPPED) |measure" || true
grep -q "FAILED" "$out/tests.log" && status=1
for sched in "${schedulers[@]}"; do
  compute-sanitizer --tool memcheck --error-exitcode 9 ./carry/gvdp render --backend cuda \
    --scheduler "$sched" --scene forest --width 320 --height 200 --frames 3 --pool-bricks 20000 \
    --out /tmp/memcheck >>"$out/sanitizer.log" 2>&1 || status=1
  echo "memcheck $sched: $(grep -E "ERROR SUMMARY" "$out/sanitizer.log" | tail -n 1)"
  # racecheck refuses binaries with device-side launches: all but dp use the GVDP_CDP=OFF build.
  race_bin=./carry/gvdp
  [ "$sched" != dp ] && [ -x ./carry/nocdp/gvdp ] && race_bin=./carry/nocdp/gvdp
  compute-sanitizer --tool racecheck --error-exitcode 9 "$race_bin" render --backend cuda \
    --scheduler "$sched" --scene perlin --width 160 --height 100 --frames 2 --pool-bricks 20000 \
    --out /tmp/racecheck >>"$out/sanitizer.log" 2>&1 || status=1
  echo "racecheck $sched: $(grep -E "ERROR SUMMARY|RACECHECK SUMMARY" "$out/sanitizer.log" | tail -n 1)"
done
for sched in "${schedulers[@]}"; do
  pngs=()
  for scene in "${scenes[@]}"; do
    dir="/tmp/render_${sched}_${scene}"
    echo "== $sched $scene" >>"$out/renders.log"
    ./carry/gvdp render --backend cuda --scheduler "$sched" --scene "$scene" --width 1500 \
      --height 1000 --frames "$frames" --out "$dir" >>"$out/renders.log" 2>&1 || status=1
    echo "$sched $scene: $(tail -n 2 "$out/renders.log" | tr '\n' ' ')"
    cp "$dir/frame_0000.png" "/tmp/${scene}.png" && pngs+=("/tmp/${scene}.png")
  done
  python3 scripts/montage.py "$out/montage_${sched}.png" "${pngs[@]}" || true
done
exit $status
