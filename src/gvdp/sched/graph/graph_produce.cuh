// The graph's production node: resident blocks claim the queued requests one brick at a time
// and run Algorithm 2 on each (produce_block.cuh).
#pragma once

#include "gvdp/profile/timeline_device.cuh"
#include "gvdp/sched/block_copy.cuh"
#include "gvdp/sched/graph/graph_frame.h"
#include "gvdp/sched/produce_block.cuh"

namespace gvdp::detail {

template <class P>
__global__ void __launch_bounds__(PRODUCE_BLOCK)
    graphProduceKernel(const GraphFrame* globalFrame, GraphLoop* loop, P producer) {
  const GraphFrame* frame = &blockCopy(globalFrame);
  BlockTimer timer(frame->frame.timeline, TaskKind::Produce);
  if (loop->stop) return;
  const CacheView& cache = frame->cache;
  uint32_t requests = cache.counters[COUNTER_REQUESTS];
  requests = requests < cache.requestCapacity ? requests : cache.requestCapacity;
  __shared__ uint32_t b;
  for (;;) {
    if (threadIdx.x == 0) b = atomicAdd(&loop->cursor, 1u);
    __syncthreads();
    if (b >= requests) return;
    produceBrickBlock(producer, cache, frame->pool, cache.requests[b]);
  }
}

template <class P>
void captureGraphProduceKernel(const GraphFrame* frame, GraphLoop* loop, const P& producer,
                               cudaStream_t stream) {
  static const int blocks = residentBlocks(graphProduceKernel<P>, PRODUCE_BLOCK);
  graphProduceKernel<<<blocks, PRODUCE_BLOCK, 0, stream>>>(frame, loop, producer);
}

}  // namespace gvdp::detail
