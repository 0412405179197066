// The `graph` scheduler: the sp loop (render pass -> production -> stopped rays -> repeat)
// captured once as a CUDA graph whose passes repeat under a conditional WHILE node (CUDA 12.4+),
// so that a frame needs no host synchronisation inside it. Images equal sp's bit for bit.
#pragma once

#include <memory>

#include "gvdp/sched/scheduler.h"

namespace gvdp {

std::unique_ptr<Scheduler> makeGraphCuda(const SchedulerOptions& options);

}  // namespace gvdp
