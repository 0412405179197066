#!/usr/bin/env bash
# On a GPU machine: ncu's per-instruction counts and stall samples of a render kernel at
# 1500x1000 (sp: its first render pass; pt: its worker kernel), and each instruction's source
# line (nvdisasm -g on the binary's cubins; the binary is built with -lineinfo):
# $OUT/sass_SCENE_SCHED.csv.gz and $OUT/lines_SCENE_SCHED.txt.gz, which scripts/ncu_lines.py joins
# (per source line) where they land. WHEN: frame20 (frame 20 of `gvdp render`'s walkthrough, the
# default), floor (the bench's fourth floor frame: the same pose again from a full cache) or
# MOVEMENT:FRAME (that frame of `gvdp render`'s path, e.g. spinning:22, a frame that produces).
# Usage: scripts/ncu_lines.sh BIN SCENE [sp|pt] [frame20|floor|MOVEMENT:FRAME]   (BIN absolute)
set -uo pipefail
bin=$1 scene=$2 sched=${3:-sp} when=${4:-frame20}
case $sched in
  sp) kernel=firstRenderPassKernel ;;
  pt) kernel=ptWorkerKernel ;;
  *) echo "ncu_lines.sh: scheduler '$sched' is not sp or pt" >&2 && exit 2 ;;
esac
# A built-in world's kernels are its own (sched/builtin_producer.cpp): the cubins hold one worker
# per world, told apart by the world's producer function in the kernel's name.
case $scene in
  perlin) world=producePerlin ;;
  fbm) world=produceFbm ;;
  forest) world=produceForest ;;
  random-spheres) world=produceRandomSpheres ;;
  aligned-spheres) world=produceAlignedSpheres ;;
  *) world= ;;
esac
name=${scene}_$sched
[[ $when == *:* ]] && name=${scene}_${when/:/_}_$sched
rep=/tmp/rep_$name
case $when in
  # One such kernel a frame: 6 warm-up and 32 measured frames, then the floor's.
  floor) skip=41 run=(bench --backend cuda --schedulers "$sched" --scenes "$scene" --movements walkthrough --out /tmp/ncu_lines.json) ;;
  frame20) skip=20 run=(render --backend cuda --scheduler "$sched" --scene "$scene" --movement walkthrough --frames 21 --width 1500 --height 1000 --out /tmp/ncu_out) ;;
  *:*) skip=${when#*:} run=(render --backend cuda --scheduler "$sched" --scene "$scene" --movement "${when%:*}" --frames $((${when#*:} + 1)) --width 1500 --height 1000 --out /tmp/ncu_out) ;;
  *) echo "ncu_lines.sh: '$when' is not frame20, floor or MOVEMENT:FRAME" >&2 && exit 2 ;;
esac
ncu --section SourceCounters --section WarpStateStats --kernel-name "regex:$kernel" --launch-skip $skip --launch-count 1 -o $rep -f \
  "$bin" "${run[@]}" >/tmp/ncu_$name.log 2>&1 || tail -n 5 /tmp/ncu_$name.log
mkdir -p "${OUT:=out/ncu_lines}"
ncu -i $rep.ncu-rep --page source --csv --print-source sass 2>&1 | gzip > $OUT/sass_$name.csv.gz
d=$(mktemp -d); (cd $d && cuobjdump -xelf all "$bin" >/dev/null 2>&1)
for f in $d/*.cubin; do
  nvdisasm -g "$f" 2>/dev/null | awk -v k="$kernel" -v w="$world" '
    /^[ \t]*\.section/ { insec = index($0, ".text.") && index($0, k) && index($0, w); if (insec) print "#SECTION", $2 }
    insec && /\/\/## File/ { loc = $0; sub(/^.*\/\/## File "/, "", loc); sub(/".*line /, ":", loc); sub(/[ ,].*$/, "", loc) }
    insec && match($0, /\/\*[0-9a-f]+\*\//) { print substr($0, RSTART + 2, RLENGTH - 4), loc }'
done | gzip > $OUT/lines_$name.txt.gz
ls -la "$OUT"
