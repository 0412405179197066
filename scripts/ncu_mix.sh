#!/usr/bin/env bash
# On a GPU machine: ncu's instruction mix (shared and global loads) and stall reasons per issued
# instruction of one frame's kernel, 1500x1000, one metric a line. Default: sp's first render
# pass of walkthrough frame 20 (BENCHMARKS.md, session 19); pt's worker in a spike frame:
#   scripts/ncu_mix.sh BIN aligned-spheres pt spinning 22
# Usage: scripts/ncu_mix.sh BIN SCENE [SCHEDULER [MOVEMENT [FRAME]]]
set -uo pipefail
bin=$1 scene=$2 sched=${3:-sp} movement=${4:-walkthrough} frame=${5:-20}
kernel=firstRenderPassKernel
[ "$sched" = pt ] && kernel=ptWorkerKernel
m=smsp__inst_executed.sum,smsp__sass_inst_executed_op_shared_ld.sum,smsp__sass_inst_executed_op_shared_st.sum,smsp__sass_inst_executed_op_global_ld.sum,smsp__inst_executed_op_shfl.sum,smsp__thread_inst_executed_per_inst_executed.ratio,gpu__time_duration.sum,smsp__issue_active.avg.pct_of_peak_sustained_active,sm__warps_active.avg.pct_of_peak_sustained_active,lts__t_sector_hit_rate.pct,l1tex__t_sector_hit_rate.pct,dram__throughput.avg.pct_of_peak_sustained_elapsed
for s in mio_throttle short_scoreboard long_scoreboard lg_throttle wait no_instruction math_pipe_throttle not_selected barrier membar branch_resolving dispatch_stall sleeping selected drain imc_miss tex_throttle; do
  m="$m,smsp__average_warps_issue_stalled_${s}_per_issue_active.ratio"
done
raw=$(mktemp)
ncu --kernel-name "regex:$kernel" --launch-skip "$frame" --launch-count 1 --csv --metrics "$m" \
  "$bin" render --backend cuda --scheduler "$sched" --scene "$scene" --movement "$movement" \
  --frames $((frame + 1)) --width 1500 --height 1000 --out /tmp/ncu_out >"$raw" 2>&1
python3 - "$raw" <<'PY' || { echo "ncu_mix: no metrics; ncu said:"; tail -n 20 "$raw"; }
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
head = next((i for i, r in enumerate(rows) if 'Metric Name' in r), None)
if head is None: sys.exit(1)
h = rows[head]
for r in rows[head + 1:]:
    if len(r) != len(h): continue
    d = dict(zip(h, r))
    print(d["Metric Name"].replace("smsp__average_warps_issue_stalled_", "stall_").replace("_per_issue_active.ratio", ""), d["Metric Value"])
PY
rm -f "$raw"
