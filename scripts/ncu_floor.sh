#!/usr/bin/env bash
# On a GPU machine: ncu's sections for a render kernel on a floor frame (the bench's re-render of
# a pose from the full cache: no production), walkthrough at 1500x1000: launch, occupancy,
# speed of light, warp states (stall reasons), instruction mix, spills. One text report per run.
# Usage: scripts/ncu_floor.sh BIN SCHEDULER SCENE [FLOOR_FRAME]
#   SCHEDULER sp (firstRenderPassKernel) or pt (ptWorkerKernel); FLOOR_FRAME 0..7 (default 3)
set -uo pipefail
bin=$1 sched=$2 scene=$3 k=${4:-3}
case $sched in
  sp) kernel=firstRenderPassKernel ;;
  pt) kernel=ptWorkerKernel ;;
  *) echo "ncu_floor.sh: scheduler '$sched' is not sp or pt" >&2 && exit 2 ;;
esac
# One kernel of each per frame: 6 warm-up frames, 32 measured, then the floor's frames.
ncu --kernel-name "regex:$kernel" --launch-skip $((38 + k)) --launch-count 1 \
  --section LaunchStats --section Occupancy --section SpeedOfLight --section WarpStateStats \
  --section InstructionStats --section ComputeWorkloadAnalysis \
  --metrics smsp__thread_inst_executed_per_inst_executed.ratio,l1tex__t_sector_hit_rate.pct,l1tex__t_sectors_pipe_lsu_mem_local_op_ld.sum,l1tex__t_sectors_pipe_lsu_mem_local_op_st.sum \
  "$bin" bench --backend cuda --schedulers "$sched" --scenes "$scene" --movements walkthrough \
  --out /tmp/ncu_floor.json 2>&1 | grep -v "^==PROF==\|^gvdp\|^  *$"
