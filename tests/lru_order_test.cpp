// The LRU order (cache/lru_order.h), rebuilt from the order before, against a stable sort of the
// slots by last-used frame, over random stamps that follow the cache's rules (a build in frame p,
// then stamps of 0, p or p + 1, marks included), frame starts and mid-frame refills, cold caches;
// on the CPU and, with a CUDA device, the GPU's order the CPU's, slot for slot.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "gvdp/cache/brick_cache_cpu.h"
#include "gvdp/cache/lru_order.h"
#include "test_util.h"
#if GVDP_HAS_CUDA
#include "gvdp/cache/brick_cache_cuda.h"
#endif

namespace gvdp::detail {
namespace {

// The slots sorted by last-used frame, stable, and the free list's length, as the sort gave them.
struct Expected {
  std::vector<uint32_t> order;
  uint32_t freeCount;
};

Expected sortedBySlotStamp(const std::vector<uint32_t>& timestamps, uint32_t frame) {
  uint32_t n = static_cast<uint32_t>(timestamps.size());
  Expected e{std::vector<uint32_t>(n), 0};
  std::iota(e.order.begin(), e.order.end(), 0u);
  std::stable_sort(e.order.begin(), e.order.end(), [&](uint32_t a, uint32_t b) {
    return lastUsedFrame(timestamps[a]) < lastUsedFrame(timestamps[b]);
  });
  uint32_t unused = 0, older = 0;
  for (uint32_t t : timestamps) {
    unused += lastUsedFrame(t) == 0;
    older += lastUsedFrame(t) < frame;
  }
  e.freeCount = freeListLength(n, unused, older);
  return e;
}

// The stamps a frame p's rays, productions, prefetch and clipmap moves leave (cache_ops.h).
void stampAsAFrame(std::vector<uint32_t>& timestamps, uint32_t p, std::mt19937& rng) {
  std::uniform_int_distribution<int> pick(0, 99);
  for (uint32_t& t : timestamps) {
    int r = pick(rng);
    if (r < 4)
      t = 0;  // resetEntry
    else if (r < 20)
      t = p;  // a ray sampled it
    else if (r < 23)
      t = p | TIMESTAMP_UNSAMPLED;  // published, not sampled yet
    else if (r < 25)
      t = (p + 1) | TIMESTAMP_MARKS;  // prefetched for the next frame
  }
}

// `builds` orders of n slots, each against the sort; `order(timestamps, frame, freeCount)` builds
// one and returns it.
template <class BuildOrder>
void expectSortedOverRandomFrames(uint32_t n, int builds, BuildOrder order) {
  std::mt19937 rng(n);
  std::vector<uint32_t> timestamps(n, 0);
  uint32_t frame = 0;
  for (int b = 0; b < builds; ++b) {
    if (b % 9 == 7) std::fill(timestamps.begin(), timestamps.end(), 0u);  // a cold cache
    if (b % 4 != 3) ++frame;  // the frame's start; else a mid-frame refill, the same frame
    uint32_t freeCount = 0;
    std::vector<uint32_t> got = order(timestamps, frame, freeCount);
    Expected e = sortedBySlotStamp(timestamps, frame);
    ASSERT_EQ(got, e.order) << "build " << b << " in frame " << frame;
    ASSERT_EQ(freeCount, e.freeCount) << "build " << b;
    stampAsAFrame(timestamps, frame, rng);
  }
}

}  // namespace

TEST(LruOrder, IsTheStableSortOfTheSlotsByLastUsedFrame) {
  for (uint32_t n : {1u, 300u, 5000u}) {
    HostCacheOps ops(n);
    expectSortedOverRandomFrames(
        n, 80, [&](const std::vector<uint32_t>& t, uint32_t frame, uint32_t& freeCount) {
          uint32_t counters[COUNTER_COUNT] = {};
          const uint32_t* order = ops.buildLruOrder(t.data(), n, frame, counters, TimelineView{});
          freeCount = counters[COUNTER_FREE_COUNT];
          return std::vector<uint32_t>(order, order + n);
        });
  }
}

#if GVDP_HAS_CUDA
TEST(LruOrder, CudaBuildsTheSortedOrderToo) {
  GVDP_REQUIRE_GPU();
  for (uint32_t n : {1u, 300u, LRU_TILE, 3 * LRU_TILE + 77, 500000u}) {
    OwnedGpuStream stream(createGpuStream());
    CudaCacheOps ops(n, stream.get());
    DeviceBuffer<uint32_t> timestamps(n), counters(COUNTER_COUNT);
    expectSortedOverRandomFrames(
        n, n > 100000 ? 10 : 60,
        [&](const std::vector<uint32_t>& t, uint32_t frame, uint32_t& freeCount) {
          writeDevice(timestamps.data(), t.data(), n * sizeof(uint32_t), stream.get());
          const uint32_t* order =
              ops.buildLruOrder(timestamps.data(), n, frame, counters.data(), TimelineView{});
          std::vector<uint32_t> got(n), c(COUNTER_COUNT);
          readDevice(got.data(), order, n * sizeof(uint32_t), stream.get());
          readDevice(c.data(), counters.data(), COUNTER_COUNT * sizeof(uint32_t), stream.get());
          freeCount = c[COUNTER_FREE_COUNT];
          return got;
        });
  }
}
#endif

}  // namespace gvdp::detail
