#include "gvdp/cache/brick_cache_cpu.h"

#include <algorithm>
#include <cstring>

#include "gvdp/base/clock.h"
#include "gvdp/base/parallel.h"
#include "gvdp/cache/cache_ops.h"
#include "gvdp/profile/timeline.h"

namespace gvdp::detail {

void HostCacheOps::fillBytes(void* p, size_t bytes, int byte) {
  std::memset(p, byte, bytes);
}

void HostCacheOps::zero(uint32_t* p, size_t n) {
  std::fill_n(p, n, 0u);
}

void HostCacheOps::read(const uint32_t* from, uint32_t* to, size_t n) {
  std::copy_n(from, n, to);
}

void HostCacheOps::resetSlabs(const CacheView& v, const SlabJobs& slabs, const TimelineView&) {
  parallelFor(
      slabs.total(), [&](int64_t i) { resetSlabItem(v, slabs, static_cast<uint32_t>(i)); }, 4096,
      static_cast<uint8_t>(TaskKind::Cache));
}

const uint32_t* HostCacheOps::sortLru(const uint32_t* timestamps, uint32_t n, uint32_t frame,
                                      uint32_t* counters, const TimelineView&) {
  for (uint32_t s = 0; s < n; ++s)
    order_[s] = (static_cast<uint64_t>(lastUsedFrame(timestamps[s])) << 32) | s;
  std::sort(order_.begin(), order_.begin() + n);
  auto below = [&](uint64_t stamp) {
    return static_cast<uint32_t>(std::lower_bound(order_.begin(), order_.begin() + n, stamp << 32) -
                                 order_.begin());
  };
  counters[COUNTER_FREE_COUNT] = freeListLength(n, below(1), below(frame));
  for (uint32_t i = 0; i < n; ++i) slots_[i] = static_cast<uint32_t>(order_[i]);
  return slots_.data();
}

void HostCacheOps::countUnsampled(uint32_t* timestamps, uint32_t n, uint32_t frame,
                                  uint32_t* counters) {
  for (uint32_t s = 0; s < n; ++s) countSlotMark(counters, takeUnsampled(&timestamps[s], frame));
}

void HostCacheOps::settleFresh(const CacheView& v, uint32_t n, const TimelineView&) {
  for (uint32_t i = 0; i < n; ++i) settleFreshSlot(v, i);
}

void HostCacheOps::setDeadline(uint64_t* at, uint64_t ns) {
  *at = clockNanoseconds() + ns;
}

void HostCacheOps::unmapSlots(const CacheView& v, uint32_t n, const TimelineView&) {
  parallelFor(
      n, [&](int64_t i) { unmapFreeSlot(v, static_cast<uint32_t>(i)); }, 4096,
      static_cast<uint8_t>(TaskKind::Cache));
}

}  // namespace gvdp::detail
