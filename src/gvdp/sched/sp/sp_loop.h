// The sp loop (paper 3.3.1, the GigaVoxels loop), written once for both backends: production of
// the queued bricks -> a render pass over the live rays -> the stopped rays -> repeat. A backend
// policy B supplies the steps (sp_cpu.cpp: SpStepsCpu, sp_cuda.cpp: SpStepsCuda):
//   cache()                          its brick cache: readCounters, view, clearRequests, refill,
//                                    setDegraded
//   void produce(uint32_t n)         Algorithm 2 on the first n queued requests
//   uint32_t renderPass(bool tiled, uint32_t live)   one pass (tiled: every pixel afresh in 8x8
//                                    tiles; else the `live` listed rays); returns the rays that
//                                    stopped on a missing brick, listed for the next pass
// The graph scheduler records the same steps as device kernels (graph/graph_kernels.cu) and
// finishes with this loop when the device cannot go on.
#pragma once

#include <algorithm>
#include <cstdint>

#include "gvdp/cache/cache_host.h"
#include "gvdp/sched/scheduler.h"
#include "gvdp/sched/sp/sp.h"

namespace gvdp::detail {

// Produces the queued bricks; a production that found no free slot refills the free list from
// the slots this frame has not used, and the frame is degraded when none is left.
template <class B>
void produceQueued(B& backend) {
  auto& cache = backend.cache();
  uint32_t before[COUNTER_COUNT], after[COUNTER_COUNT];
  cache.readCounters(before);
  uint32_t requests = std::min(before[COUNTER_REQUESTS], cache.view().requestCapacity);
  if (requests == 0) return;
  backend.produce(requests);
  cache.clearRequests();
  cache.readCounters(after);
  if (after[COUNTER_FAILED] != before[COUNTER_FAILED] && cache.refill() == 0)
    cache.setDegraded(true);
}

// Runs passes until no ray is left. With `tiled`, the first pass covers every pixel from a fresh
// state, at the frame's start (BrickCache::beginFrame has emptied the queue: no read of its
// count, a host round trip before the first ray); otherwise it resumes `liveCount` listed rays
// (none: only the queued bricks are produced), after producing the bricks already queued. Adds
// to stats.passes; past SP_MAX_PASSES the frame is marked degraded.
template <class B>
void runSpLoop(B& backend, uint32_t liveCount, bool tiled, FrameStats& stats) {
  if (!tiled) produceQueued(backend);
  if (liveCount == 0 && !tiled) return;
  for (int pass = 0;; ++pass) {
    liveCount = backend.renderPass(pass == 0 && tiled, liveCount);
    ++stats.passes;
    if (liveCount == 0) break;
    produceQueued(backend);
    if (stats.passes >= SP_MAX_PASSES) backend.cache().setDegraded(true);
  }
  // Past a budgeted frame's deadline rays claim bricks and go on: those are produced now, for the
  // next frames. (Without a budget every claim has a stopped ray: nothing is left queued.)
  if (backend.cache().budgeted()) produceQueued(backend);
}

}  // namespace gvdp::detail
