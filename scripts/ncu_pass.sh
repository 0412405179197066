#!/usr/bin/env bash
# On a GPU machine: ncu's figures for one render pass of frame 20 of a 1500x1000 walkthrough
# (warp instructions, lanes per instruction, issue slots busy, warps active, L1 hit rate,
# registers, duration under the profiler), printed as one line.
# Usage: scripts/ncu_pass.sh NAME BIN SCENE [SCHEDULER] [KERNEL_REGEX]
#   (default: sp, firstRenderPassKernel; BENCHMARKS.md, session 18)
set -uo pipefail
name=$1 bin=$2 scene=$3 sched=${4:-sp} kernel=${5:-firstRenderPassKernel}
csv=$(mktemp)
trap 'rm -rf "$csv" "$csv.out"' EXIT
ncu --kernel-name "regex:$kernel" --launch-skip 20 --launch-count 1 --csv --metrics \
  smsp__inst_executed.sum,smsp__thread_inst_executed_per_inst_executed.ratio,gpu__time_duration.sum,smsp__issue_active.avg.pct_of_peak_sustained_active,l1tex__t_sector_hit_rate.pct,sm__warps_active.avg.pct_of_peak_sustained_active,launch__registers_per_thread \
  "$bin" render --backend cuda --scheduler "$sched" --scene "$scene" --movement walkthrough \
  --frames 21 --width 1500 --height 1000 --out "$csv.out" >"$csv" 2>&1
python3 - "$csv" "$name" "$scene" <<'PY'
import csv, sys
rows = [r for r in csv.reader(open(sys.argv[1])) if len(r) > 10]
if not rows:
    sys.exit(f"{sys.argv[2]} {sys.argv[3]}: ncu printed no metrics")
head = rows[0]
values = [dict(zip(head, r)) for r in rows[1:]]
print(sys.argv[2], sys.argv[3], " ".join(f"{v['Metric Name']}={v['Metric Value']}" for v in values))
PY
