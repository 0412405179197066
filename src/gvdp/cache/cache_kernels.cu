// CUDA kernels of the cache maintenance: clipmap slab reset, LRU sort (CUB), unmapping.
#include <cub/device/device_radix_sort.cuh>

#include "gvdp/cache/cache_kernels.h"
#include "gvdp/profile/timeline_device.cuh"

namespace gvdp {
namespace {

constexpr int BLOCK = 256;
inline unsigned blocksFor(uint32_t n) {
  return (n + BLOCK - 1) / BLOCK;
}

__global__ void resetSlabsKernel(CacheView cache, SlabJobs jobs) {
  BlockTimer timer(TaskKind::Cache);
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < jobs.total()) resetSlabItem(cache, jobs, i);
}

__global__ void prepareLruSortKernel(const uint32_t* timestamps, uint32_t* keys, uint32_t* values,
                                     uint32_t n) {
  BlockTimer timer(TaskKind::Cache);
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) {
    keys[i] = timestamps[i];
    values[i] = i;
  }
}

__global__ void countOlderKernel(const uint32_t* sortedKeys, uint32_t n, uint32_t frame,
                                 uint32_t* count) {
  BlockTimer timer(TaskKind::Cache);
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  // Sorted ascending: the keys below `frame` are a prefix; its last element writes the length.
  if (i < n && sortedKeys[i] < frame && (i + 1 == n || sortedKeys[i + 1] >= frame)) *count = i + 1;
}

__global__ void unmapSlotsKernel(CacheView cache, const uint32_t* slots, uint32_t n) {
  BlockTimer timer(TaskKind::Cache);
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) unmapSlot(cache, slots[i]);
}

}  // namespace

void launchResetSlabs(const CacheView& cache, const SlabJobs& jobs) {
  if (jobs.total()) resetSlabsKernel<<<blocksFor(jobs.total()), BLOCK>>>(cache, jobs);
}

void launchPrepareLruSort(const uint32_t* timestamps, uint32_t* keys, uint32_t* values,
                          uint32_t n) {
  prepareLruSortKernel<<<blocksFor(n), BLOCK>>>(timestamps, keys, values, n);
}

size_t lruSortTempBytes(uint32_t n) {
  size_t bytes = 0;
  cub::DeviceRadixSort::SortPairs(
      nullptr, bytes, static_cast<const uint32_t*>(nullptr), static_cast<uint32_t*>(nullptr),
      static_cast<const uint32_t*>(nullptr), static_cast<uint32_t*>(nullptr), n);
  return bytes;
}

void lruSort(void* temp, size_t tempBytes, const uint32_t* keysIn, uint32_t* keysOut,
             const uint32_t* valuesIn, uint32_t* valuesOut, uint32_t n, int endBit) {
  cub::DeviceRadixSort::SortPairs(temp, tempBytes, keysIn, keysOut, valuesIn, valuesOut, n, 0,
                                  endBit);
}

void launchCountOlder(const uint32_t* sortedKeys, uint32_t n, uint32_t frame, uint32_t* count) {
  if (n) countOlderKernel<<<blocksFor(n), BLOCK>>>(sortedKeys, n, frame, count);
}

void launchUnmapSlots(const CacheView& cache, const uint32_t* slots, uint32_t n) {
  if (n) unmapSlotsKernel<<<blocksFor(n), BLOCK>>>(cache, slots, n);
}

}  // namespace gvdp
