#!/usr/bin/env bash
# On a GPU machine: ncu's per-instruction counts and stall samples of sp's first render pass
# (walkthrough frame 20, 1500x1000), and each instruction's source line (nvdisasm -g on the
# binary's cubins; the binary is built with -lineinfo): $OUT/sass_SCENE.csv.gz and
# $OUT/lines_SCENE.txt.gz, which scripts/ncu_lines.py joins (per source line) where they land.
# Usage: scripts/ncu_lines.sh BIN SCENE   (BIN an absolute path; BENCHMARKS.md, session 19)
set -uo pipefail
bin=$1 scene=$2
ncu --section SourceCounters --section WarpStateStats --kernel-name regex:firstRenderPassKernel --launch-skip 20 --launch-count 1 -o /tmp/rep_$scene -f \
  "$bin" render --backend cuda --scheduler sp --scene "$scene" --movement walkthrough --frames 21 \
  --width 1500 --height 1000 --out /tmp/ncu_out >/tmp/ncu_$scene.log 2>&1 || tail -n 5 /tmp/ncu_$scene.log
mkdir -p "${OUT:=out/ncu_lines}"
ncu -i /tmp/rep_$scene.ncu-rep --page source --csv --print-source sass 2>&1 | gzip > $OUT/sass_$scene.csv.gz
d=$(mktemp -d); (cd $d && cuobjdump -xelf all "$bin" >/dev/null 2>&1)
for f in $d/*.cubin; do
  nvdisasm -g "$f" 2>/dev/null | awk '
    /^[ \t]*\.section/ { insec = ($0 ~ /firstRenderPassKernel/); if (insec) print "#SECTION", $2 }
    insec && /\/\/## File/ { loc = $0; sub(/^.*\/\/## File "/, "", loc); sub(/".*line /, ":", loc); sub(/[ ,].*$/, "", loc) }
    insec && match($0, /\/\*[0-9a-f]+\*\//) { print substr($0, RSTART + 2, RLENGTH - 4), loc }'
done | gzip > $OUT/lines_$scene.txt.gz
ls -la "$OUT"
