// Algorithm 2 (cache/produce.h) as a CUDA block of PRODUCE_BLOCK threads, two samples per
// thread. Shared by the sp, dp and graph production kernels.
#pragma once

#include "gvdp/cache/produce.h"
#include "gvdp/render/brick_pool.h"

namespace gvdp::detail {

constexpr int PRODUCE_BLOCK = 512;

template <class P>
__device__ inline void produceBrickBlock(const P& producer, const CacheView& cache,
                                         const BrickPool& pool, const BrickKey& key) {
  __shared__ uint32_t word;
  constexpr int PER = (BRICK_SAMPLE_COUNT + PRODUCE_BLOCK - 1) / PRODUCE_BLOCK;
  produceBrick<PER>(BlockScope{&word}, producer, cache, pool, key);
}

}  // namespace gvdp::detail
