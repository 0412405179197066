#!/usr/bin/env bash
# On a machine with a GPU, with the binaries built elsewhere and carried in carry/: every test
# (GPU ones included), then a short 1500x1000 render of each scene per scheduler. Writes to $OUT
# (or out/gpu_check): device.txt, tests.log, renders.log and frame 0 of each scene of the first
# scheduler. Usage: scripts/gpu_check.sh [frames] [schedulers...]
set -uo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-out/gpu_check}"
mkdir -p "$out"
frames="${1:-8}"
shift || true
schedulers=("${@:-direct}")
export GVDP_BIN="$PWD/carry/gvdp"
nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader | tee "$out/device.txt"
status=0
./carry/gvdp_tests 2>&1 | tee "$out/tests.log" | grep -E "^\[  (FAILED|PASSED|SKIPPED) |measure" || true
grep -q "FAILED" "$out/tests.log" && status=1
for sched in "${schedulers[@]}"; do
  for scene in perlin fbm forest random-spheres aligned-spheres; do
    dir="/tmp/render_${sched}_${scene}"
    echo "== $sched $scene" >>"$out/renders.log"
    ./carry/gvdp render --backend cuda --scheduler "$sched" --scene "$scene" --width 1500 \
      --height 1000 --frames "$frames" --out "$dir" >>"$out/renders.log" 2>&1 || status=1
    echo "$sched $scene: $(tail -n 1 "$out/renders.log")"
    [ "$sched" = "${schedulers[0]}" ] && cp "$dir/frame_0000.png" "$out/${scene}.png" 2>/dev/null
  done
done
exit $status
