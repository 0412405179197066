// What a scheduler will hold for a frame size, computed before anything is allocated, so that a
// configuration too large for its backend is refused in one line instead of failing in an
// allocation. The items carry the names and bytes the scheduler's memory() reports after a frame
// (tests check this on the CPU), plus what memory() leaves out: the output image, the host-side
// LRU sort, dp's sweep lists. Approximate on CUDA only where the device decides: cub's sort
// scratch (about one copy of keys and values) and pt's worker count; dp's pending-launch buffer
// (sized by the device runtime) is not counted.
#pragma once

#include <cstdint>
#include <optional>

#include "gvdp/render/frame.h"
#include "gvdp/sched/scheduler.h"

namespace gvdp::detail {

MemoryReport memoryEstimate(const SchedulerOptions& options, const FrameSetup& frame);
uint64_t memoryTotal(const MemoryReport& report);

// What the backend can hold now: the host's available memory, or the device's free memory;
// nullopt when it cannot be told.
std::optional<uint64_t> backendMemoryBytes(Backend backend);

}  // namespace gvdp::detail
