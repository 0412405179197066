#include "gvdp/cache/brick_cache_cuda.h"

#include <algorithm>
#include <bit>

#include "gvdp/cache/cache_kernels.h"

namespace gvdp {

BrickCacheCuda::BrickCacheCuda(uint32_t poolBricks)
    : poolBricks_(poolBricks),
      timestamps_(poolBricks),
      counters_(COUNTER_COUNT),
      inverse_(poolBricks),
      sortKeysIn_(poolBricks),
      sortKeysOut_(poolBricks),
      sortValuesIn_(poolBricks),
      sortValuesOut_(poolBricks),
      freeCount_(2),
      sortTemp_(lruSortTempBytes(poolBricks)) {
  GVDP_INPUT_CHECK(poolBricks >= 1 && poolBricks < MAX_SLOTS, "bad --pool-bricks ", poolBricks);
  texels_ = DeviceBuffer<Rgba8>(static_cast<size_t>(poolBricks) * BRICK_SAMPLE_COUNT);
  pool_.texels = texels_.data();
}

void BrickCacheCuda::beginFrame(const FrameSetup& frame) {
  NvtxRange range("cache: clipmap move and LRU refill");
  ClipmapTracker::Update u = tracker_.next(frame);
  clipmap_ = u.clipmap;
  timeline_ = frame.timeline;
  GVDP_CUDA_CHECK(cudaMemset(counters_.data(), 0, counters_.bytes()));
  degraded_ = false;
  ++frame_;
  if (u.fullReset) {
    if (entries_.size() != clipmap_.entryCount())
      entries_ = DeviceBuffer<uint32_t>(clipmap_.entryCount());
    GVDP_CUDA_CHECK(cudaMemset(entries_.data(), 0xff, entries_.bytes()));  // ENTRY_MISSING
    GVDP_CUDA_CHECK(cudaMemset(timestamps_.data(), 0, timestamps_.bytes()));
    GVDP_CUDA_CHECK(cudaMemset(inverse_.data(), 0xff, inverse_.bytes()));  // level NO_LEVEL
    resident_ = 0;
  } else {
    launchResetSlabs(view(), u.slabs, timeline_);
  }
  size_t rays = static_cast<size_t>(frame.pixelCount());
  if (requests_.size() < rays) requests_ = DeviceBuffer<BrickKey>(rays);
  refill();
  refills_ = 0;
}

uint32_t BrickCacheCuda::refill() {
  launchPrepareLruSort(timestamps_.data(), sortKeysIn_.data(), sortValuesIn_.data(), poolBricks_,
                       timeline_);
  int endBit = std::max(1, static_cast<int>(std::bit_width(frame_)));
  lruSort(sortTemp_.data(), sortTemp_.size(), sortKeysIn_.data(), sortKeysOut_.data(),
          sortValuesIn_.data(), sortValuesOut_.data(), poolBricks_, endBit);
  GVDP_CUDA_CHECK(cudaMemset(freeCount_.data(), 0, freeCount_.bytes()));
  launchCountOlder(sortKeysOut_.data(), poolBricks_, 1u, freeCount_.data(), timeline_);
  launchCountOlder(sortKeysOut_.data(), poolBricks_, frame_, freeCount_.data() + 1, timeline_);
  uint32_t counts[2];
  GVDP_CUDA_CHECK(cudaMemcpy(counts, freeCount_.data(), sizeof counts, cudaMemcpyDeviceToHost));
  freeCountHost_ = freeListLength(poolBricks_, counts[0], counts[1]);
  GVDP_CUDA_CHECK(cudaMemset(counters_.data() + COUNTER_FREE_NEXT, 0, sizeof(uint32_t)));
  // The free slot list is the head of the sorted slots (oldest first).
  launchUnmapSlots(view(), sortValuesOut_.data(), freeCountHost_, timeline_);
  GVDP_CUDA_CHECK(cudaGetLastError());
  ++refills_;
  return freeCountHost_;
}

CacheView BrickCacheCuda::view() const {
  CacheView v{};
  v.clipmap = clipmap_;
  v.entries = entries_.data();
  v.timestamps = timestamps_.data();
  v.inverse = inverse_.data();
  v.freeSlots = sortValuesOut_.data();
  v.freeCount = freeCountHost_;
  v.requests = requests_.data();
  v.requestCapacity = static_cast<uint32_t>(requests_.size());
  v.counters = counters_.data();
  v.frame = frame_;
  v.degraded = degraded_ ? 1u : 0u;
  return v;
}

void BrickCacheCuda::readCounters(uint32_t* out) const {
  GVDP_CUDA_CHECK(cudaMemcpy(out, counters_.data(), counters_.bytes(), cudaMemcpyDeviceToHost));
}

void BrickCacheCuda::clearRequests() {
  GVDP_CUDA_CHECK(cudaMemset(counters_.data() + COUNTER_REQUESTS, 0, sizeof(uint32_t)));
}

CacheStats BrickCacheCuda::frameStats() {
  uint32_t c[COUNTER_COUNT];
  readCounters(c);
  resident_ = resident_ + c[COUNTER_PRODUCED] - c[COUNTER_EVICTED];
  return cacheStatsFrom(c, resident_, refills_);
}

MemoryReport BrickCacheCuda::memory() const {
  return {{"brick_pool", texels_.bytes()},
          {"indirection_table", entries_.bytes()},
          {"inverse_table", inverse_.bytes()},
          {"timestamps", timestamps_.bytes()},
          {"free_slot_list_and_lru_sort", sortKeysIn_.bytes() + sortKeysOut_.bytes() +
                                              sortValuesIn_.bytes() + sortValuesOut_.bytes() +
                                              sortTemp_.bytes()},
          {"request_queue", requests_.bytes()}};
}

}  // namespace gvdp
