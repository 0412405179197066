// The CUDA backend's brick cache: BrickCache (brick_cache.h) over device buffers, the bodies of
// cache_ops.h launched from cache_kernels.cu, the LRU order by a CUB radix sort of the
// timestamps.
#pragma once

#include <cstdint>

#include "gvdp/base/cuda_util.h"
#include "gvdp/cache/brick_cache.h"

namespace gvdp::detail {

class CudaCacheOps {
 public:
  template <class T>
  using Buffer = DeviceBuffer<T>;
  static constexpr const char* LRU_NAME = "free_slot_list_and_lru_sort";

  // Every operation runs on `stream` (the scheduler's).
  CudaCacheOps(uint32_t poolBricks, cudaStream_t stream);

  template <class T>
  void fillBytes(DeviceBuffer<T>& b, int byte) const {
    fillDevice(b.data(), byte, b.bytes(), stream_);
  }
  void zero(uint32_t* p, size_t n) const;
  void read(const uint32_t* from, uint32_t* to, size_t n) const;  // synchronises
  void resetSlabs(const CacheView& v, const SlabJobs& slabs, const TimelineView& t) const;
  const uint32_t* sortLru(const uint32_t* timestamps, uint32_t n, uint32_t frame,
                          uint32_t* counters, const TimelineView& t);
  void unmapSlots(const CacheView& v, uint32_t n, const TimelineView& t) const;
  void countUnsampled(uint32_t* timestamps, uint32_t n, uint32_t frame, uint32_t* counters) const;
  void settleFresh(const CacheView& v, uint32_t n, const TimelineView& t) const;
  void setDeadline(uint64_t* at, uint64_t ns) const;
  size_t lruBytes() const;

 private:
  cudaStream_t stream_;
  DeviceBuffer<uint32_t> keysIn_, keysOut_, valuesIn_, valuesOut_, counts_;
  DeviceBuffer<uint8_t> temp_;
};

using BrickCacheCuda = BrickCache<CudaCacheOps>;

}  // namespace gvdp::detail
