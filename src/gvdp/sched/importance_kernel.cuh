// CUDA kernels of the importance pre-pass (importance.h): a thread per pre-pass ray, a warp per
// listed brick, a thread per table slot; the bodies the CPU runs.
#pragma once

#include <algorithm>

#include "gvdp/sched/importance.h"

namespace gvdp::detail {

template <class P>
__global__ void countRayBricksKernel(FrameSetup frame, P producer, ImportanceSetup setup) {
  uint32_t ray = blockIdx.x * blockDim.x + threadIdx.x;
  if (ray < setup.rays()) countRayBricks(frame, producer, setup, ray);
}

// A warp per listed brick: lane l reads samples l, l + 32, ... until a lane finds one occupied.
template <class P>
__global__ void classifyImportanceKernel(FrameSetup frame, P producer, ImportanceSetup setup) {
  uint32_t lane = threadIdx.x % 32, warps = gridDim.x * blockDim.x / 32;
  uint32_t bricks = setup.status[IMPORTANCE_BRICKS];
  for (uint32_t b = (blockIdx.x * blockDim.x + threadIdx.x) / 32; b < bricks; b += warps) {
    uint64_t slot = setup.bricks[b];
    BrickKey brick = importanceBrick(frame, setup.table[slot]);
    bool occupied = false;
    for (int first = 0; first < BRICK_SAMPLE_COUNT && !occupied; first += 32) {
      int k = first + static_cast<int>(lane);
      bool mine = k < BRICK_SAMPLE_COUNT && importanceSampleOccupied(producer, brick, k);
      occupied = __any_sync(0xffffffffu, mine);
    }
    if (lane == 0) setup.occupied[slot] = occupied ? 1 : 0;
  }
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
  constexpr uint32_t CLASSIFY_BLOCKS = 4096;  // grid-stride over the bricks (counted on the device)
  classifyImportanceKernel<<<CLASSIFY_BLOCKS, BLOCK, 0, stream>>>(frame, producer, setup);
  auto grid = static_cast<uint32_t>(
      std::clamp<uint64_t>((setup.tableSize() + BLOCK - 1) / BLOCK, 1, uint64_t{1} << 16));
  countImportanceKernel<<<grid, BLOCK, 0, stream>>>(setup);
}

}  // namespace gvdp::detail
