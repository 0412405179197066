// The `pt` scheduler (persistent threads): one persistent kernel per frame whose warps pull
// production tasks, relaunched rays and fresh screen tiles from device work queues; the same
// protocol on worker threads on the CPU (pt_body.h). No CDP, no pending-launch buffer.
#pragma once

#include <cstdint>
#include <memory>

#include "gvdp/sched/scheduler.h"

namespace gvdp::detail {

// The GPU's producer SMs, one per S productions of backlog (pt_worker.cuh: roleNow): S = 2
// unless GVDP_PT_PRODUCER_SHARE=S says otherwise (0: none, helper SMs only). Throws InputError
// naming any value but an integer 0..4096.
inline constexpr uint32_t PT_PRODUCER_SHARE_DEFAULT = 2;
uint32_t ptProducerShareFromEnvironment();

// In a spike frame (pt_cuda.cpp: spikeBacklogOf) the first 5/8 of the SMs only produce and the
// others render (pt_body.h: ptRole). Every warp taking any work there, as before, ran SMs whose
// instruction caches held the production and the march at once: random-spheres forward's exit
// frame waited for instructions in 67% of its stall samples (ncu, H200). Against that, 25 pt
// cells x 3 rounds (H200, BENCHMARKS.md session 64): 4/8 1% lows x1.017, 5/8 x1.046, 6/8 x1.011;
// random-spheres' and fbm's slowest frames 10-14% shorter, a frame from an empty cache at most
// 180 -> 147 ms.
inline constexpr uint32_t PT_SPIKE_PRODUCER_EIGHTHS = 5;

// pt's far prefetch (pt_prefetch.h: prefetchPlanAfter): at most this many predicted frames
// (SchedulerOptions::farPrefetch, `--far-prefetch`).
inline constexpr uint32_t PT_FAR_MAX_POSES = MAX_FAR_PREFETCH;

std::unique_ptr<Scheduler> makePtCpu(const SchedulerOptions& options, ProducerKernelsPtr producer);
std::unique_ptr<Scheduler> makePtCuda(const SchedulerOptions& options, ProducerKernelsPtr producer);

}  // namespace gvdp::detail
