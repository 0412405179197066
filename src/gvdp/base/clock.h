// One clock for CPU tasks and GPU kernels, in nanoseconds: the steady clock on the host,
// %globaltimer on the device (each against its own epoch: compare readings of one side only).
// Timeline records and a frame's budget (cache_view.h: the deadline) are measured on it.
#pragma once

#include <chrono>
#include <cstdint>

#include "gvdp/base/defs.h"

namespace gvdp::detail {

GVDP_HD GVDP_INLINE uint64_t clockNanoseconds() {
#if GVDP_IS_GPU_CODE
  uint64_t t;
  asm volatile("mov.u64 %0, %%globaltimer;" : "=l"(t));
  return t;
#else
  return static_cast<uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                   std::chrono::steady_clock::now().time_since_epoch())
                                   .count());
#endif
}

}  // namespace gvdp::detail
