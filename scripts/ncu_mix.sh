#!/usr/bin/env bash
# On a GPU machine: ncu's instruction mix (shared and global loads) and stall reasons per issued
# instruction of sp's first render pass, walkthrough frame 20, 1500x1000, one metric a line.
# Usage: scripts/ncu_mix.sh BIN SCENE   (BENCHMARKS.md, session 19)
set -uo pipefail
bin=$1 scene=$2
m=smsp__inst_executed.sum,smsp__sass_inst_executed_op_shared_ld.sum,smsp__sass_inst_executed_op_shared_st.sum,smsp__sass_inst_executed_op_global_ld.sum,smsp__inst_executed_op_shfl.sum,smsp__thread_inst_executed_per_inst_executed.ratio,gpu__time_duration.sum,smsp__issue_active.avg.pct_of_peak_sustained_active,sm__warps_active.avg.pct_of_peak_sustained_active
for s in mio_throttle short_scoreboard long_scoreboard lg_throttle wait no_instruction math_pipe_throttle not_selected barrier membar branch_resolving dispatch_stall; do
  m="$m,smsp__average_warps_issue_stalled_${s}_per_issue_active.ratio"
done
ncu --kernel-name regex:firstRenderPassKernel --launch-skip 20 --launch-count 1 --csv --metrics "$m" \
  "$bin" render --backend cuda --scheduler sp --scene "$scene" --movement walkthrough --frames 21 \
  --width 1500 --height 1000 --out /tmp/ncu_out 2>&1 | python3 -c '
import csv, sys
rows = [r for r in csv.reader(sys.stdin) if len(r) > 10]
if not rows: sys.exit("no metrics")
h = rows[0]
for r in rows[1:]:
    d = dict(zip(h, r)); print(d["Metric Name"].replace("smsp__average_warps_issue_stalled_","stall_").replace("_per_issue_active.ratio",""), d["Metric Value"])
'
