// CUDA kernels of the cache maintenance: clipmap slab reset, LRU sort (CUB), unmapping, the
// frame's deadline, the fresh marks' settling.
#include <cub/device/device_radix_sort.cuh>

#include "gvdp/base/clock.h"
#include "gvdp/cache/cache_kernels.h"
#include "gvdp/profile/parallel_for.cuh"

namespace gvdp::detail {

void launchResetSlabs(const CacheView& cache, const SlabJobs& jobs, const TimelineView& timeline,
                      cudaStream_t stream) {
  parallelForCuda("cache: reset slabs", stream, jobs.total(), timeline, TaskKind::Cache,
                  [=] __device__(uint32_t i) { resetSlabItem(cache, jobs, i); });
}

void launchPrepareLruSort(const uint32_t* timestamps, uint32_t* keys, uint32_t* values, uint32_t n,
                          const TimelineView& timeline, cudaStream_t stream) {
  parallelForCuda("cache: LRU sort keys", stream, n, timeline, TaskKind::Cache,
                  [=] __device__(uint32_t i) {
                    keys[i] = lastUsedFrame(timestamps[i]);
                    values[i] = i;
                  });
}

size_t lruSortTempBytes(uint32_t n) {
  size_t bytes = 0;
  cub::DeviceRadixSort::SortPairs(
      nullptr, bytes, static_cast<const uint32_t*>(nullptr), static_cast<uint32_t*>(nullptr),
      static_cast<const uint32_t*>(nullptr), static_cast<uint32_t*>(nullptr), n);
  return bytes;
}

void lruSort(void* temp, size_t tempBytes, const uint32_t* keysIn, uint32_t* keysOut,
             const uint32_t* valuesIn, uint32_t* valuesOut, uint32_t n, int endBit,
             cudaStream_t stream) {
  GVDP_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(temp, tempBytes, keysIn, keysOut, valuesIn,
                                                  valuesOut, n, 0, endBit, stream));
}

void launchCountOlder(const uint32_t* sortedKeys, uint32_t n, uint32_t frame, uint32_t* count,
                      const TimelineView& timeline, cudaStream_t stream) {
  // Sorted ascending: the keys below `frame` are a prefix; its last element writes the length.
  parallelForCuda("cache: count older", stream, n, timeline, TaskKind::Cache,
                  [=] __device__(uint32_t i) {
                    if (sortedKeys[i] < frame && (i + 1 == n || sortedKeys[i + 1] >= frame))
                      *count = i + 1;
                  });
}

void launchCountUnsampled(uint32_t* timestamps, uint32_t n, uint32_t frame, uint32_t* counters,
                          const TimelineView& timeline, cudaStream_t stream) {
  parallelForCuda("cache: count unsampled", stream, n, timeline, TaskKind::Cache,
                  [=] __device__(uint32_t i) {
                    countSlotMark(counters, takeUnsampled(&timestamps[i], frame));
                  });
}

void launchFreeListLength(const uint32_t* counts, uint32_t poolBricks, uint32_t* counters,
                          cudaStream_t stream) {
  parallelForCuda("cache: free list length", stream, 1, TimelineView{}, TaskKind::Cache,
                  [=] __device__(uint32_t) {
                    counters[COUNTER_FREE_COUNT] = freeListLength(poolBricks, counts[0], counts[1]);
                  });
}

void launchSetDeadline(uint64_t* at, uint64_t ns, cudaStream_t stream) {
  parallelForCuda("cache: deadline", stream, 1, TimelineView{}, TaskKind::Cache,
                  [=] __device__(uint32_t) { *at = clockNanoseconds() + ns; });
}

void launchUnmapSlots(const CacheView& cache, uint32_t n, const TimelineView& timeline,
                      cudaStream_t stream) {
  parallelForCuda("cache: unmap slots", stream, n, timeline, TaskKind::Cache,
                  [=] __device__(uint32_t i) { unmapFreeSlot(cache, i); });
}

void launchSettleFresh(const CacheView& cache, uint32_t n, const TimelineView& timeline,
                       cudaStream_t stream) {
  parallelForCuda("cache: settle fresh entries", stream, n, timeline, TaskKind::Cache,
                  [=] __device__(uint32_t i) { settleFreshSlot(cache, i); });
}

}  // namespace gvdp::detail
