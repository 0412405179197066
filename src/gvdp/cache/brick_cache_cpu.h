// The CPU backend's brick cache: BrickCache (brick_cache.h) over host vectors, the bodies of
// cache_ops.h run on the thread pool, the LRU order rebuilt in two passes (lru_order.h).
#pragma once

#include <cstdint>
#include <vector>

#include "gvdp/cache/brick_cache.h"

namespace gvdp::detail {

class HostCacheOps {
 public:
  template <class T>
  using Buffer = std::vector<T>;
  static constexpr const char* LRU_NAME = "lru_order";

  explicit HostCacheOps(uint32_t poolBricks);

  template <class T>
  static void fillBytes(std::vector<T>& b, int byte) {
    fillBytes(b.data(), b.size() * sizeof(T), byte);
  }
  static void fillBytes(void* p, size_t bytes, int byte);
  static void zero(uint32_t* p, size_t n);
  static void read(const uint32_t* from, uint32_t* to, size_t n);
  static void resetSlabs(const CacheView& v, const SlabJobs& slabs, const TimelineView&);
  const uint32_t* buildLruOrder(const uint32_t* timestamps, uint32_t n, uint32_t frame,
                                uint32_t* counters, const TimelineView&);
  static void countUnsampled(uint32_t* timestamps, uint32_t n, uint32_t frame, uint32_t* counters);
  static void settleFresh(const CacheView& v, uint32_t n, const TimelineView&);
  static void growTableBoxes(const CacheView& v, const TimelineView&);
  static void tableBoxesReady() {}
  static void joinTableBoxes() {}  // grown before growTableBoxes returns
  static void startFrame(const CacheView& v, uint32_t settle, int64_t deadlineNs,
                         const TimelineView&);
  static void unmapSlots(const CacheView& v, uint32_t n, const TimelineView&);
  size_t lruBytes() const { return (order_.size() + next_.size()) * sizeof(uint32_t); }

 private:
  std::vector<uint32_t> order_;  // the slots, oldest first: the free slot list is its head
  std::vector<uint32_t> next_;   // the next order, built from order_
  uint32_t builtAt_ = 0;         // the frame order_ was built in
};

using BrickCacheCpu = BrickCache<HostCacheOps>;

}  // namespace gvdp::detail
