// The GPU twin of parallelFor (base/parallel.h): fn(i) for every i in [0, n), one launch on
// `stream` of a grid-stride kernel sized by occupancy (at most the blocks resident on the device at
// once), under an NVTX range and recorded on the timeline as `kind`, one record per block. For
// element-wise work only: lanes past n leave the loop, so fn must not need the whole warp. Its
// blocks may start while the stream's kernel before it ends, and wait for it
// (base/dependent_launch.cuh); the next kernel's may start as soon as all of its own run.
#pragma once

#include <algorithm>

#include "gvdp/base/cuda_util.h"
#include "gvdp/base/dependent_launch.cuh"
#include "gvdp/profile/timeline_device.cuh"

namespace gvdp::detail {

template <class Fn>
__global__ void parallelForKernel(uint32_t n, TimelineView timeline, TaskKind kind, Fn fn) {
  awaitPriorGrids();
  releaseDependentGrids();
  BlockTimer timer(timeline, kind);
  for (uint32_t i = blockIdx.x * blockDim.x + threadIdx.x; i < n; i += gridDim.x * blockDim.x)
    fn(i);
}

template <class Fn>
void parallelForCuda(const char* name, cudaStream_t stream, uint32_t n,
                     const TimelineView& timeline, TaskKind kind, Fn fn) {
  constexpr int BLOCK = 256;
  if (n == 0) return;
  NvtxRange range(name);
  static const int resident = residentBlocks(parallelForKernel<Fn>, BLOCK);
  uint32_t blocks = std::min<uint32_t>((n + BLOCK - 1) / BLOCK, static_cast<uint32_t>(resident));
  launchDependent(parallelForKernel<Fn>, blocks, BLOCK, stream, n, timeline, kind, fn);
}

}  // namespace gvdp::detail
