// sp's production kernel: Algorithm 2, one block per queued request (produce_block.cuh).
#pragma once

#include "gvdp/profile/timeline_device.cuh"
#include "gvdp/sched/produce_block.cuh"

namespace gvdp::detail {

template <class P>
__global__ void __launch_bounds__(PRODUCE_BLOCK)
    produceKernel(FrameSetup f, CacheView cache, BrickPool pool, P producer) {
  BlockTimer timer(f.timeline, TaskKind::Produce);
  produceBrickBlock(producer, cache, pool, cache.requests[blockIdx.x]);
}

template <class P>
void launchProduceKernel(const FrameSetup& f, const CacheView& cache, const BrickPool& pool,
                         const P& producer, uint32_t requests, cudaStream_t stream) {
  if (requests) produceKernel<<<requests, PRODUCE_BLOCK, 0, stream>>>(f, cache, pool, producer);
}

}  // namespace gvdp::detail
