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

// pt's far prefetch (pt_prefetch.h: prefetchPlanAfter): at most this many predicted frames
// (SchedulerOptions::farPrefetch, `--far-prefetch`).
inline constexpr uint32_t PT_FAR_MAX_POSES = MAX_FAR_PREFETCH;

std::unique_ptr<Scheduler> makePtCpu(const SchedulerOptions& options, ProducerKernelsPtr producer);
std::unique_ptr<Scheduler> makePtCuda(const SchedulerOptions& options, ProducerKernelsPtr producer);

}  // namespace gvdp::detail
