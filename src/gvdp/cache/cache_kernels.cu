// CUDA kernels of the cache maintenance: clipmap slab reset, the LRU order (lru_order.h),
// unmapping, the frame's start (its counters and deadline), the fresh marks' settling.
#include <cub/block/block_reduce.cuh>
#include <cub/block/block_scan.cuh>

#include "gvdp/base/clock.h"
#include "gvdp/base/cooperation.h"
#include "gvdp/base/dependent_launch.cuh"
#include "gvdp/cache/cache_kernels.h"
#include "gvdp/cache/lru_order.h"
#include "gvdp/cache/table_boxes.h"
#include "gvdp/profile/parallel_for.cuh"

namespace gvdp::detail {

void launchResetSlabs(const CacheView& cache, const SlabJobs& jobs, const TimelineView& timeline,
                      cudaStream_t stream) {
  parallelForCuda("cache: reset slabs", stream, jobs.total(), timeline, TaskKind::Cache,
                  [=] __device__(uint32_t i) { resetSlabItem(cache, jobs, i); });
}

namespace {

constexpr int LRU_THREADS = 256;
constexpr int LRU_ITEMS = static_cast<int>(LRU_TILE) / LRU_THREADS;  // per thread, in index order
static_assert(LRU_TILE < (1u << 16), "a tile's part sizes are 16-bit fields");

// One count in part `part`'s 16-bit field (none for LRU_PARTS).
__device__ uint64_t lruField(uint32_t part) {
  return part < LRU_PARTS ? 1ull << (16 * part) : 0ull;
}

__device__ uint32_t lruFieldOf(uint64_t sizes, uint32_t part) {
  return static_cast<uint32_t>(sizes >> (16 * part)) & 0xffffu;
}

// Thread threadIdx.x's items of the tile (lruItemAt), in index order, and their sizes in 16-bit
// fields.
struct LruItems {
  LruItem item[LRU_ITEMS];
  uint64_t sizes = 0;

  __device__ LruItems(const uint32_t* timestamps, const uint32_t* order, uint32_t n,
                      uint32_t builtAt) {
    uint32_t first = blockIdx.x * LRU_TILE + threadIdx.x * LRU_ITEMS;
    for (int j = 0; j < LRU_ITEMS; ++j) {
      uint32_t i = first + static_cast<uint32_t>(j);
      item[j] = i < n ? lruItemAt(timestamps, order, i, builtAt) : LruItem{LRU_PARTS, MAX_SLOTS};
      sizes += lruField(item[j].part) + (item[j].kept != MAX_SLOTS ? lruField(LRU_KEPT) : 0ull);
    }
  }
};

// Pass 1: each tile's part sizes.
__global__ void __launch_bounds__(LRU_THREADS)
    lruTileSizesKernel(const uint32_t* timestamps, const uint32_t* order, uint32_t n,
                       uint32_t builtAt, uint64_t* tileSizes, TimelineView timeline) {
  awaitPriorGrids();
  releaseDependentGrids();
  BlockTimer timer(timeline, TaskKind::Cache);
  using Reduce = cub::BlockReduce<uint64_t, LRU_THREADS>;
  __shared__ typename Reduce::TempStorage temp;
  LruItems items(timestamps, order, n, builtAt);
  uint64_t sizes = Reduce(temp).Sum(items.sizes);
  if (threadIdx.x == 0) tileSizes[blockIdx.x] = sizes;
}

// The tiles' part sizes before this one and in all, per part.
struct LruSums {
  uint32_t before[LRU_PARTS], all[LRU_PARTS];
};

struct AddLruSums {
  __device__ LruSums operator()(const LruSums& a, const LruSums& b) const {
    LruSums s;
    for (uint32_t p = 0; p < LRU_PARTS; ++p) {
      s.before[p] = a.before[p] + b.before[p];
      s.all[p] = a.all[p] + b.all[p];
    }
    return s;
  }
};

// Pass 2: each item to its place, parts one after the other, in item order within a part; the
// free list's length from the first tile.
__global__ void __launch_bounds__(LRU_THREADS)
    lruScatterKernel(const uint32_t* timestamps, const uint32_t* order, uint32_t* next, uint32_t n,
                     uint32_t builtAt, uint32_t frame, const uint64_t* tileSizes, uint32_t tiles,
                     uint32_t* counters, TimelineView timeline) {
  awaitPriorGrids();
  releaseDependentGrids();
  BlockTimer timer(timeline, TaskKind::Cache);
  using Reduce = cub::BlockReduce<LruSums, LRU_THREADS>;
  using Scan = cub::BlockScan<uint64_t, LRU_THREADS>;
  __shared__ union {
    typename Reduce::TempStorage reduce;
    typename Scan::TempStorage scan;
  } temp;
  __shared__ uint32_t start[LRU_PARTS];
  LruSums sums{};
  for (uint32_t t = threadIdx.x; t < tiles; t += LRU_THREADS) {
    uint64_t sizes = tileSizes[t];
    for (uint32_t p = 0; p < LRU_PARTS; ++p) {
      sums.all[p] += lruFieldOf(sizes, p);
      if (t < blockIdx.x) sums.before[p] += lruFieldOf(sizes, p);
    }
  }
  sums = Reduce(temp.reduce).Reduce(sums, AddLruSums{});
  if (threadIdx.x == 0) {
    uint32_t at = 0;
    for (uint32_t p = 0; p < LRU_PARTS; ++p) {
      start[p] = at + sums.before[p];
      at += sums.all[p];
    }
    if (blockIdx.x == 0) {
      counters[COUNTER_FREE_COUNT] = lruFreeListLength(n, sums.all, builtAt, frame);
      counters[COUNTER_FREE_NEXT] = 0;  // the list taken from its head
    }
  }
  __syncthreads();
  LruItems items(timestamps, order, n, builtAt);
  uint64_t rank;
  Scan(temp.scan).ExclusiveSum(items.sizes, rank);
  uint32_t first = blockIdx.x * LRU_TILE + threadIdx.x * LRU_ITEMS;
  for (int j = 0; j < LRU_ITEMS; ++j) {
    const LruItem& item = items.item[j];
    if (item.part < LRU_PARTS) {
      next[start[item.part] + lruFieldOf(rank, item.part)] = first + static_cast<uint32_t>(j);
      rank += lruField(item.part);
    }
    if (item.kept != MAX_SLOTS) {
      next[start[LRU_KEPT] + lruFieldOf(rank, LRU_KEPT)] = item.kept;
      rank += lruField(LRU_KEPT);
    }
  }
}

}  // namespace

void launchLruOrder(const uint32_t* timestamps, const uint32_t* order, uint32_t* next, uint32_t n,
                    uint32_t builtAt, uint32_t frame, uint64_t* tileSizes, uint32_t* counters,
                    const TimelineView& timeline, cudaStream_t stream) {
  uint32_t tiles = lruTileCount(n);
  launchDependent(lruTileSizesKernel, tiles, LRU_THREADS, stream, timestamps, order, n, builtAt,
                  tileSizes, timeline);
  launchDependent(lruScatterKernel, tiles, LRU_THREADS, stream, timestamps, order, next, n, builtAt,
                  frame, tileSizes, tiles, counters, timeline);
}

void launchCountUnsampled(uint32_t* timestamps, uint32_t n, uint32_t frame, uint32_t* counters,
                          const TimelineView& timeline, cudaStream_t stream) {
  parallelForCuda("cache: count unsampled", stream, n, timeline, TaskKind::Cache,
                  [=] __device__(uint32_t i) {
                    countSlotMark(counters, takeUnsampled(&timestamps[i], frame));
                  });
}

void launchUnmapSlots(const CacheView& cache, uint32_t n, const TimelineView& timeline,
                      cudaStream_t stream) {
  parallelForCuda("cache: unmap slots", stream, n, timeline, TaskKind::Cache,
                  [=] __device__(uint32_t i) { unmapFreeSlot(cache, i); });
}

void launchSettleFresh(const CacheView& cache, uint32_t n, const TimelineView& timeline,
                       cudaStream_t stream) {
  parallelForCuda("cache: settle fresh entries", stream, n, timeline, TaskKind::Cache,
                  [=] __device__(uint32_t i) { settleFreshSlot(cache, i); });
}

// Blocks of one warp, each taking the next item (COUNTER_GROWN_NEXT) until none is left: a block
// runs where a frame's kernels leave room, beside them or as they end, and takes less work if it
// starts late.
__global__ void growTableBoxesKernel(CacheView cache, TimelineView timeline) {
  BlockTimer timer(timeline, TaskKind::Cache);
  const WarpScope warp{static_cast<int>(threadIdx.x)};
  for (;;) {
    uint32_t item = 0;
    if (threadIdx.x == 0) item = atomicAdd(&cache.counters[COUNTER_GROWN_NEXT], 1u);
    item = __shfl_sync(0xffffffffu, item, 0);
    if (item >= listedItems(cache)) return;
    growTableBox(warp, cache, item);
  }
}

void launchGrowTableBoxes(const CacheView& cache, const TimelineView& timeline,
                          cudaStream_t stream) {
  constexpr int BLOCKS_PER_SM = 8;
  NvtxRange range("cache: grow table boxes");
  static const int sms = smCount();
  growTableBoxesKernel<<<sms * BLOCKS_PER_SM, 32, 0, stream>>>(cache, timeline);
  GVDP_CUDA_CHECK(cudaGetLastError());
}

void launchStartFrame(const CacheView& cache, uint32_t settle, int64_t deadlineNs,
                      const TimelineView& timeline, cudaStream_t stream) {
  uint32_t n = settle > COUNTER_COUNT ? settle : static_cast<uint32_t>(COUNTER_COUNT);
  parallelForCuda("cache: frame start", stream, n, timeline, TaskKind::Cache,
                  [=] __device__(uint32_t i) {
                    if (i < settle) settleFreshSlot(cache, i);
                    if (i < COUNTER_COUNT) startFrameCounter(cache.counters, i, deadlineNs);
                  });
}

}  // namespace gvdp::detail
