// The CPU backend's brick cache: BrickCache (brick_cache.h) over host vectors, the bodies of
// cache_ops.h run on the thread pool, the LRU order by std::sort.
#pragma once

#include <cstdint>
#include <vector>

#include "gvdp/cache/brick_cache.h"

namespace gvdp::detail {

class HostCacheOps {
 public:
  template <class T>
  using Buffer = std::vector<T>;
  static constexpr const char* LRU_NAME = "free_slot_list_and_lru_sort";

  explicit HostCacheOps(uint32_t poolBricks) : order_(poolBricks), slots_(poolBricks) {}

  template <class T>
  static void fillBytes(std::vector<T>& b, int byte) {
    fillBytes(b.data(), b.size() * sizeof(T), byte);
  }
  static void fillBytes(void* p, size_t bytes, int byte);
  static void zero(uint32_t* p, size_t n);
  static void read(const uint32_t* from, uint32_t* to, size_t n);
  static void resetSlabs(const CacheView& v, const SlabJobs& slabs, const TimelineView&);
  const uint32_t* sortLru(const uint32_t* timestamps, uint32_t n, uint32_t frame,
                          uint32_t* counters, const TimelineView&);
  static void countUnsampled(uint32_t* timestamps, uint32_t n, uint32_t frame, uint32_t* counters);
  static void settleFresh(const CacheView& v, uint32_t n, const TimelineView&);
  static void setDeadline(uint64_t* at, uint64_t ns);
  static void unmapSlots(const CacheView& v, uint32_t n, const TimelineView&);
  size_t lruBytes() const {
    return slots_.size() * sizeof(uint32_t) + order_.size() * sizeof(uint64_t);
  }

 private:
  std::vector<uint64_t> order_;  // (timestamp, slot), the sort's keys
  std::vector<uint32_t> slots_;  // the slots, oldest first: the free slot list is its head
};

using BrickCacheCpu = BrickCache<HostCacheOps>;

}  // namespace gvdp::detail
