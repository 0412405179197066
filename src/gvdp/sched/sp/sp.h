// The `sp` scheduler (GigaVoxels, static parallelism): render pass over the live rays -> the
// queue of requested bricks (unique by the MISSING -> IN_PRODUCTION CAS) -> production pass ->
// the compacted list of stopped rays -> repeat until no ray is left; the host reads the counts
// after every pass. When the free slot list runs dry it is refilled from the slots unused in
// this frame; when none are left the frame is degraded (rays fall back to coarser levels).
#pragma once

#include <memory>

#include "gvdp/sched/scheduler.h"

namespace gvdp::detail {

std::unique_ptr<Scheduler> makeSpCpu(const SchedulerOptions& options, ProducerKernelsPtr producer);
std::unique_ptr<Scheduler> makeSpCuda(const SchedulerOptions& options, ProducerKernelsPtr producer);

// Passes after which a frame stops producing and finishes its rays degraded (a safety net: a
// normal frame needs a few dozen).
constexpr int SP_MAX_PASSES = 4096;

}  // namespace gvdp::detail
