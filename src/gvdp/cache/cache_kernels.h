// Launchers of the CUDA cache maintenance kernels (cache_kernels.cu), on the cache's stream,
// recorded on `timeline` (the frame's, FrameSetup::timeline).
#pragma once

#include <cuda_runtime_api.h>

#include <cstddef>

#include "gvdp/cache/cache_ops.h"
#include "gvdp/profile/timeline.h"

namespace gvdp::detail {

void launchResetSlabs(const CacheView& cache, const SlabJobs& jobs, const TimelineView& timeline,
                      cudaStream_t stream);
// next = the LRU order of the n slots in `frame`, from `order` built in frame builtAt
// (lru_order.h); counters[COUNTER_FREE_COUNT] = the free list's length,
// counters[COUNTER_FREE_NEXT] = 0. tileSizes: lruTileCount(n) words.
void launchLruOrder(const uint32_t* timestamps, const uint32_t* order, uint32_t* next, uint32_t n,
                    uint32_t builtAt, uint32_t frame, uint64_t* tileSizes, uint32_t* counters,
                    const TimelineView& timeline, cudaStream_t stream);
// The slots' marks at the end of `frame` into `counters` (CacheCounter; takeUnsampled).
void launchCountUnsampled(uint32_t* timestamps, uint32_t n, uint32_t frame, uint32_t* counters,
                          const TimelineView& timeline, cudaStream_t stream);
// A frame's start: settleFreshSlot(cache, i) for i < settle and startFrameCounter for every
// counter (cache_ops.h), one launch.
void launchStartFrame(const CacheView& cache, uint32_t settle, int64_t deadlineNs,
                      const TimelineView& timeline, cudaStream_t stream);
// growTableBox(warp, cache, i) for the listed items (table_boxes.h: listedItems), a warp each,
// in blocks of one warp that take items until none is left.
void launchGrowTableBoxes(const CacheView& cache, const TimelineView& timeline,
                          cudaStream_t stream);
// settleFreshSlot(cache, i) for i < n (cache_ops.h).
void launchSettleFresh(const CacheView& cache, uint32_t n, const TimelineView& timeline,
                       cudaStream_t stream);
// unmapFreeSlot(cache, i) for i < n (cache_ops.h).
void launchUnmapSlots(const CacheView& cache, uint32_t n, const TimelineView& timeline,
                      cudaStream_t stream);

}  // namespace gvdp::detail
