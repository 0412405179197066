// CUDA kernels of the importance pre-pass (importance.h): one thread per pre-pass ray, then one
// per table slot twice, the bodies the CPU runs.
#pragma once

#include <algorithm>

#include "gvdp/sched/importance.h"

namespace gvdp::detail {

template <class P>
__global__ void countRayBricksKernel(FrameSetup frame, P producer, ImportanceSetup setup) {
  uint32_t ray = blockIdx.x * blockDim.x + threadIdx.x;
  if (ray < setup.rays()) countRayBricks(frame, producer, setup, ray);
}

template <class P>
__global__ void classifyImportanceKernel(FrameSetup frame, P producer, ImportanceSetup setup) {
  for (uint64_t slot = blockIdx.x * uint64_t{blockDim.x} + threadIdx.x; slot < setup.tableSize();
       slot += uint64_t{gridDim.x} * blockDim.x)
    classifyImportanceBrick(frame, producer, setup, slot);
}

template <int = 0>  // a template: one definition however many translation units include it
__global__ void countImportanceKernel(ImportanceSetup setup) {
  for (uint64_t slot = blockIdx.x * uint64_t{blockDim.x} + threadIdx.x; slot < setup.tableSize();
       slot += uint64_t{gridDim.x} * blockDim.x)
    countImportanceNode(setup, slot);
}

template <class P>
void launchCountBricksKernel(const FrameSetup& frame, const P& producer,
                             const ImportanceSetup& setup, cudaStream_t stream) {
  constexpr uint32_t BLOCK = 128;
  uint32_t n = setup.rays();
  if (n == 0) return;
  countRayBricksKernel<<<(n + BLOCK - 1) / BLOCK, BLOCK, 0, stream>>>(frame, producer, setup);
  auto grid = static_cast<uint32_t>(std::min<uint64_t>(setup.tableSize() / BLOCK, 1u << 16));
  classifyImportanceKernel<<<grid, BLOCK, 0, stream>>>(frame, producer, setup);
  countImportanceKernel<<<grid, BLOCK, 0, stream>>>(setup);
}

}  // namespace gvdp::detail
