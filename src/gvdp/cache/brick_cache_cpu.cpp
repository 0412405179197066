#include "gvdp/cache/brick_cache_cpu.h"

#include <algorithm>
#include <cstring>
#include <numeric>

#include "gvdp/base/clock.h"
#include "gvdp/base/parallel.h"
#include "gvdp/cache/cache_ops.h"
#include "gvdp/cache/lru_order.h"
#include "gvdp/cache/table_boxes.h"
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

HostCacheOps::HostCacheOps(uint32_t poolBricks) : order_(poolBricks), next_(poolBricks) {
  std::iota(order_.begin(), order_.end(), 0u);  // a pool never used, in order
}

const uint32_t* HostCacheOps::buildLruOrder(const uint32_t* timestamps, uint32_t n, uint32_t frame,
                                            uint32_t* counters, const TimelineView&) {
  uint32_t size[LRU_PARTS] = {};
  for (uint32_t i = 0; i < n; ++i) {
    LruItem item = lruItemAt(timestamps, order_.data(), i, builtAt_);
    if (item.part < LRU_PARTS) ++size[item.part];
    if (item.kept != MAX_SLOTS) ++size[LRU_KEPT];
  }
  uint32_t at[LRU_PARTS] = {};
  for (uint32_t part = 1; part < LRU_PARTS; ++part) at[part] = at[part - 1] + size[part - 1];
  for (uint32_t i = 0; i < n; ++i) {
    LruItem item = lruItemAt(timestamps, order_.data(), i, builtAt_);
    if (item.part < LRU_PARTS) next_[at[item.part]++] = i;
    if (item.kept != MAX_SLOTS) next_[at[LRU_KEPT]++] = item.kept;
  }
  counters[COUNTER_FREE_COUNT] = lruFreeListLength(n, size, builtAt_, frame);
  counters[COUNTER_FREE_NEXT] = 0;  // the list taken from its head
  order_.swap(next_);
  builtAt_ = frame;
  return order_.data();
}

void HostCacheOps::countUnsampled(uint32_t* timestamps, uint32_t n, uint32_t frame,
                                  uint32_t* counters) {
  for (uint32_t s = 0; s < n; ++s) countSlotMark(counters, takeUnsampled(&timestamps[s], frame));
}

void HostCacheOps::settleFresh(const CacheView& v, uint32_t n, const TimelineView&) {
  for (uint32_t i = 0; i < n; ++i) settleFreshSlot(v, i);
}

void HostCacheOps::growTableBoxes(const CacheView& v, const TimelineView&) {
  uint32_t items = listedItems(v);
  parallelFor(
      items, [&](int64_t i) { growTableBox(ThreadScope{}, v, static_cast<uint32_t>(i)); }, 16,
      static_cast<uint8_t>(TaskKind::Cache));
}

void HostCacheOps::startFrame(const CacheView& v, uint32_t settle, int64_t deadlineNs,
                              const TimelineView& t) {
  settleFresh(v, settle, t);
  for (uint32_t i = 0; i < COUNTER_COUNT; ++i) startFrameCounter(v.counters, i, deadlineNs);
}

void HostCacheOps::unmapSlots(const CacheView& v, uint32_t n, const TimelineView&) {
  parallelFor(
      n, [&](int64_t i) { unmapFreeSlot(v, static_cast<uint32_t>(i)); }, 4096,
      static_cast<uint8_t>(TaskKind::Cache));
}

}  // namespace gvdp::detail
