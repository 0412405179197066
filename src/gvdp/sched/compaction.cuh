// Thread compaction (seed 004): the stopped rays of a warp are appended with one atomic, so the
// next pass runs over full warps of live rays only. Shared by the sp and graph kernels.
#pragma once

#include <cstdint>

#include "gvdp/base/bits.h"

namespace gvdp::detail {

// Every lane of the warp must call it.
__device__ inline void appendStopped(bool stopped, uint32_t pixel, uint32_t* next,
                                     uint32_t* count) {
  unsigned mask = __ballot_sync(0xffffffffu, stopped);
  if (mask == 0) return;
  int lane = threadIdx.x & 31, leader = lowestBit(mask);
  uint32_t base = 0;
  if (lane == leader) base = atomicAdd(count, static_cast<uint32_t>(__popc(mask)));
  base = __shfl_sync(0xffffffffu, base, leader);
  if (stopped) next[base + __popc(mask & ((1u << lane) - 1u))] = pixel;
}

}  // namespace gvdp::detail
