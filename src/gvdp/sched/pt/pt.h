// The `pt` scheduler (persistent threads): one persistent kernel per frame whose warps pull
// production tasks, relaunched rays and fresh screen tiles from device work queues; the same
// protocol on worker threads on the CPU (pt_body.h). No CDP, no pending-launch buffer.
#pragma once

#include <memory>

#include "gvdp/sched/scheduler.h"

namespace gvdp::detail {

std::unique_ptr<Scheduler> makePtCpu(const SchedulerOptions& options, ProducerKernelsPtr producer);
std::unique_ptr<Scheduler> makePtCuda(const SchedulerOptions& options, ProducerKernelsPtr producer);

}  // namespace gvdp::detail
