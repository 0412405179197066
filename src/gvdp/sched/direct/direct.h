// The `direct` scheduler: the uncached reference renderer, one ray per pixel, on either backend.
#pragma once

#include <memory>

#include "gvdp/sched/scheduler.h"

namespace gvdp {

std::unique_ptr<Scheduler> makeDirectCpu();
std::unique_ptr<Scheduler> makeDirectCuda();  // throws when built without CUDA

}  // namespace gvdp
