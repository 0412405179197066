#include "gvdp/cache/brick_cache_cpu.h"

#include <algorithm>
#include <cstring>

#include "gvdp/base/error.h"
#include "gvdp/base/parallel.h"
#include "gvdp/cache/cache_ops.h"
#include "gvdp/profile/timeline.h"

namespace gvdp {

BrickCacheCpu::BrickCacheCpu(uint32_t poolBricks)
    : poolBricks_(poolBricks),
      timestamps_(poolBricks, 0u),
      inverse_(poolBricks, BrickKey{{0, 0, 0}, NO_LEVEL}),
      texels_(static_cast<size_t>(poolBricks) * BRICK_SAMPLE_COUNT, 0u) {
  GVDP_INPUT_CHECK(poolBricks >= 1 && poolBricks < MAX_SLOTS, "bad --pool-bricks ", poolBricks);
  freeSlots_.resize(poolBricks);
}

void BrickCacheCpu::beginFrame(const FrameSetup& frame) {
  ClipmapTracker::Update u = tracker_.next(frame);
  clipmap_ = u.clipmap;
  std::memset(counters_, 0, sizeof counters_);
  degraded_ = false;
  refills_ = 0;
  ++frame_;
  if (u.fullReset) {
    entries_.assign(clipmap_.entryCount(), ENTRY_MISSING);
    std::fill(timestamps_.begin(), timestamps_.end(), 0u);
    std::fill(inverse_.begin(), inverse_.end(), BrickKey{{0, 0, 0}, NO_LEVEL});
  } else {
    CacheView v = view();
    parallelFor(
        u.slabs.total(), [&](int64_t i) { resetSlabItem(v, u.slabs, static_cast<uint32_t>(i)); },
        4096, static_cast<uint8_t>(TaskKind::Cache));
  }
  size_t rays = static_cast<size_t>(frame.pixelCount());
  if (requests_.size() < rays) requests_.resize(rays);
  refill();
  refills_ = 0;
}

uint32_t BrickCacheCpu::refill() {
  // LRU: slots by (timestamp, slot), oldest first; only those not used in this frame.
  std::vector<uint64_t> order(poolBricks_);
  for (uint32_t s = 0; s < poolBricks_; ++s)
    order[s] = (static_cast<uint64_t>(timestamps_[s]) << 32) | s;
  std::sort(order.begin(), order.end());
  auto below = [&](uint64_t stamp) {
    return static_cast<uint32_t>(std::lower_bound(order.begin(), order.end(), stamp << 32) -
                                 order.begin());
  };
  uint32_t n = freeListLength(poolBricks_, below(1), below(frame_));
  for (uint32_t i = 0; i < n; ++i) freeSlots_[i] = static_cast<uint32_t>(order[i]);
  freeCount_ = n;
  counters_[COUNTER_FREE_NEXT] = 0;
  CacheView v = view();
  parallelFor(
      n, [&](int64_t i) { unmapSlot(v, freeSlots_[i]); }, 256,
      static_cast<uint8_t>(TaskKind::Cache));
  ++refills_;
  return n;
}

CacheView BrickCacheCpu::view() {
  CacheView v{};
  v.clipmap = clipmap_;
  v.entries = entries_.data();
  v.timestamps = timestamps_.data();
  v.inverse = inverse_.data();
  v.freeSlots = freeSlots_.data();
  v.freeCount = freeCount_;
  v.requests = requests_.data();
  v.requestCapacity = static_cast<uint32_t>(requests_.size());
  v.counters = counters_;
  v.frame = frame_;
  v.degraded = degraded_ ? 1u : 0u;
  return v;
}

CacheStats BrickCacheCpu::frameStats() const {
  auto resident = std::count_if(inverse_.begin(), inverse_.end(),
                                [](const BrickKey& k) { return k.level != NO_LEVEL; });
  return cacheStatsFrom(counters_, static_cast<uint64_t>(resident), refills_);
}

MemoryReport BrickCacheCpu::memory() const {
  return {{"brick_pool", texels_.size() * sizeof(Rgba8)},
          {"indirection_table", entries_.size() * sizeof(uint32_t)},
          {"inverse_table", inverse_.size() * sizeof(BrickKey)},
          {"timestamps", timestamps_.size() * sizeof(uint32_t)},
          {"free_slot_list", freeSlots_.size() * sizeof(uint32_t)},
          {"request_queue", requests_.size() * sizeof(BrickKey)}};
}

}  // namespace gvdp
