// Algorithm 2 as a CUDA block: one thread per sample (two per thread for a 512-thread block),
// block-wide AND of the empty flags, thread 0 takes a slot, the block writes the samples, fence,
// thread 0 publishes the entry. Shared by the sp and dp production kernels.
#pragma once

#include "gvdp/cache/cache_ops.h"
#include "gvdp/cache/produce.h"
#include "gvdp/render/brick_pool.h"

namespace gvdp {

constexpr int PRODUCE_BLOCK = 512;

__device__ inline void produceBrickBlock(const SceneParams& scene, const CacheView& cache,
                                         const BrickPool& pool, const BrickKey& key) {
  __shared__ uint32_t slot;
  Rgba8 values[2] = {0u, 0u};
  bool empty = true;
  for (int k = 0; k < 2; ++k) {
    int s = static_cast<int>(threadIdx.x) + k * PRODUCE_BLOCK;
    if (s < BRICK_SAMPLE_COUNT) {
      VoxelSample v = produceBrickSample(scene, key, s);
      values[k] = v.rgba;
      empty = empty && v.empty;
    }
  }
  empty = __syncthreads_and(empty);
  if (threadIdx.x == 0) slot = empty ? MAX_SLOTS : takeFreeSlot(cache);
  __syncthreads();
  if (!empty && slot != MAX_SLOTS) {
    for (int k = 0; k < 2; ++k) {
      int s = static_cast<int>(threadIdx.x) + k * PRODUCE_BLOCK;
      if (s < BRICK_SAMPLE_COUNT) pool.write(slot, s, values[k]);
    }
    __threadfence();
  }
  __syncthreads();
  if (threadIdx.x == 0) publishBrick(cache, key, empty, slot);
}

}  // namespace gvdp
