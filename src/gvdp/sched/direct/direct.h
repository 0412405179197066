// The `direct` scheduler: the uncached reference renderer, one ray per pixel, on either backend.
#pragma once

#include <memory>

#include "gvdp/sched/scheduler.h"

namespace gvdp::detail {

std::unique_ptr<Scheduler> makeDirectCpu(ProducerKernelsPtr producer);
std::unique_ptr<Scheduler> makeDirectCuda(ProducerKernelsPtr producer);  // CUDA builds only

}  // namespace gvdp::detail
