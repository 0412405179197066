// The CUDA backend's brick cache: BrickCache (brick_cache.h) over device buffers, the bodies of
// cache_ops.h launched from cache_kernels.cu, the LRU order rebuilt in two kernels (lru_order.h).
#pragma once

#include <cstdint>

#include "gvdp/base/cuda_util.h"
#include "gvdp/cache/brick_cache.h"

namespace gvdp::detail {

class CudaCacheOps {
 public:
  template <class T>
  using Buffer = DeviceBuffer<T>;
  static constexpr const char* LRU_NAME = "lru_order";

  // Every operation runs on `stream` (the scheduler's).
  CudaCacheOps(uint32_t poolBricks, cudaStream_t stream);
  ~CudaCacheOps();
  CudaCacheOps(const CudaCacheOps&) = delete;
  CudaCacheOps& operator=(const CudaCacheOps&) = delete;

  template <class T>
  void fillBytes(DeviceBuffer<T>& b, int byte) const {
    fillDevice(b.data(), byte, b.bytes(), stream_);
  }
  void zero(uint32_t* p, size_t n) const;
  void read(const uint32_t* from, uint32_t* to, size_t n) const;  // synchronises
  void resetSlabs(const CacheView& v, const SlabJobs& slabs, const TimelineView& t) const;
  const uint32_t* buildLruOrder(const uint32_t* timestamps, uint32_t n, uint32_t frame,
                                uint32_t* counters, const TimelineView& t);
  void unmapSlots(const CacheView& v, uint32_t n, const TimelineView& t) const;
  void countUnsampled(uint32_t* timestamps, uint32_t n, uint32_t frame, uint32_t* counters) const;
  void settleFresh(const CacheView& v, uint32_t n, const TimelineView& t) const;
  // On a stream of its own, after the work queued on `stream` before tableBoxesReady, beside
  // what follows it (joinTableBoxes: `stream` waits for it).
  void tableBoxesReady() const;
  void growTableBoxes(const CacheView& v, const TimelineView& t) const;
  void joinTableBoxes() const;
  void startFrame(const CacheView& v, uint32_t settle, int64_t deadlineNs,
                  const TimelineView& t) const;
  size_t lruBytes() const;

 private:
  cudaStream_t stream_;
  cudaStream_t boxes_;                   // the table boxes' growth (growTableBoxes)
  cudaEvent_t queued_, grown_;           // stream_'s work before it; its end
  DeviceBuffer<uint32_t> order_, next_;  // the LRU order and the next, built from it (lru_order.h)
  DeviceBuffer<uint64_t> tileSizes_;     // each tile's part sizes (launchLruOrder)
  uint32_t builtAt_ = 0;                 // the frame order_ was built in
};

using BrickCacheCuda = BrickCache<CudaCacheOps>;

}  // namespace gvdp::detail
