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
// keys[i] = lastUsedFrame(timestamps[i]), values[i] = i.
void launchPrepareLruSort(const uint32_t* timestamps, uint32_t* keys, uint32_t* values, uint32_t n,
                          const TimelineView& timeline, cudaStream_t stream);
size_t lruSortTempBytes(uint32_t n);
void lruSort(void* temp, size_t tempBytes, const uint32_t* keysIn, uint32_t* keysOut,
             const uint32_t* valuesIn, uint32_t* valuesOut, uint32_t n, int endBit,
             cudaStream_t stream);
// The slots' marks at the end of `frame` into `counters` (CacheCounter; takeUnsampled).
void launchCountUnsampled(uint32_t* timestamps, uint32_t n, uint32_t frame, uint32_t* counters,
                          const TimelineView& timeline, cudaStream_t stream);
// *count = how many of the first n sorted keys are below frame.
void launchCountOlder(const uint32_t* sortedKeys, uint32_t n, uint32_t frame, uint32_t* count,
                      const TimelineView& timeline, cudaStream_t stream);
// counters[COUNTER_FREE_COUNT] = freeListLength(poolBricks, counts[0], counts[1]) (cache_ops.h).
void launchFreeListLength(const uint32_t* counts, uint32_t poolBricks, uint32_t* counters,
                          cudaStream_t stream);
// *at = the device's clockNanoseconds() + ns, when the stream reaches it.
void launchSetDeadline(uint64_t* at, uint64_t ns, cudaStream_t stream);
// settleFreshSlot(cache, i) for i < n (cache_ops.h).
void launchSettleFresh(const CacheView& cache, uint32_t n, const TimelineView& timeline,
                       cudaStream_t stream);
// unmapFreeSlot(cache, i) for i < n (cache_ops.h).
void launchUnmapSlots(const CacheView& cache, uint32_t n, const TimelineView& timeline,
                      cudaStream_t stream);

}  // namespace gvdp::detail
