#include <cub/block/block_scan.cuh>
#include <utility>

#include "gvdp/base/dependent_launch.cuh"
#include "gvdp/profile/timeline_device.cuh"
#include "gvdp/sched/tile_order_cuda.h"

namespace gvdp::detail {
namespace {

constexpr int ORDER_THREADS = 1024, ORDER_WARPS = ORDER_THREADS / 32;
constexpr int ORDER_BUCKETS = 256;  // blockCostKey's values
constexpr int ORDER_SCAN_ITEMS = ORDER_BUCKETS * ORDER_WARPS / ORDER_THREADS;
static_assert(ORDER_BUCKETS * ORDER_WARPS % ORDER_THREADS == 0, "each thread scans whole items");

// One block orders frame f's n blocks by the costs `before` measured (tile_order.h), most costly
// first and row-major among equals, and zeroes f's own costs (`fresh`): a stable counting sort
// over the 256 keys, in one launch (the frame's start was bound by its launches: BENCHMARKS.md,
// session 31). Each warp takes a run of the blocks, 32 at a time, and counts its blocks per key;
// an exclusive scan over (key, warp), keys most costly first, gives each warp its first place per
// key; then each warp places its blocks in their order. `keys`: n words of scratch.
__global__ void __launch_bounds__(ORDER_THREADS)
    tileOrderKernel(const FrameSetup f, const FrameSetup before, const uint32_t* cost,
                    uint32_t* fresh, uint32_t* keys, uint32_t* order, uint32_t n) {
  awaitPriorGrids();
  releaseDependentGrids();
  BlockTimer timer(f.timeline, TaskKind::Cache);
  using Scan = cub::BlockScan<uint32_t, ORDER_THREADS>;
  __shared__ typename Scan::TempStorage scan;
  __shared__ uint32_t place[ORDER_BUCKETS * ORDER_WARPS];  // [bucket][warp]: counts, then places
  for (uint32_t i = threadIdx.x; i < ORDER_BUCKETS * ORDER_WARPS; i += ORDER_THREADS) place[i] = 0;
  __syncthreads();
  const uint32_t lane = threadIdx.x & 31u, warp = threadIdx.x >> 5;
  const uint32_t run = (n + ORDER_WARPS - 1) / ORDER_WARPS;
  const uint32_t begin = min(n, warp * run), end = min(n, begin + run);
  for (uint32_t first = begin; first < end; first += 32) {
    uint32_t i = first + lane, bucket = ORDER_BUCKETS;  // bucket 0: the most costly key
    if (i < end) {
      int r = reprojectedBlock(f, before, static_cast<int>(i));
      bucket = ORDER_BUCKETS - 1 - blockCostKey(neighbourhoodCost(cost, before, r));
      keys[i] = bucket;
      fresh[i] = 0;
    }
    uint32_t peers = __match_any_sync(~0u, bucket);
    if (bucket < ORDER_BUCKETS && lane == __ffs(peers) - 1u)
      place[bucket * ORDER_WARPS + warp] += __popc(peers);
    __syncwarp();
  }
  __syncthreads();
  uint32_t* mine = place + threadIdx.x * ORDER_SCAN_ITEMS;  // consecutive (bucket, warp) entries
  uint32_t sum = 0;
  for (int k = 0; k < ORDER_SCAN_ITEMS; ++k) sum += mine[k];
  uint32_t at;
  Scan(scan).ExclusiveSum(sum, at);
  for (int k = 0; k < ORDER_SCAN_ITEMS; ++k) {
    uint32_t c = mine[k];
    mine[k] = at;
    at += c;
  }
  __syncthreads();
  for (uint32_t first = begin; first < end; first += 32) {
    uint32_t i = first + lane, bucket = i < end ? keys[i] : ORDER_BUCKETS;
    uint32_t peers = __match_any_sync(~0u, bucket);
    if (bucket < ORDER_BUCKETS)
      order[place[bucket * ORDER_WARPS + warp] + __popc(peers & ((1u << lane) - 1u))] = i;
    __syncwarp();
    if (bucket < ORDER_BUCKETS && lane == __ffs(peers) - 1u)
      place[bucket * ORDER_WARPS + warp] += __popc(peers);
    __syncwarp();
  }
}

}  // namespace

TileOrder TileOrderCuda::next(const FrameSetup& f, cudaStream_t stream) {
  const uint32_t n = static_cast<uint32_t>(orderBlockCount(f));
  const bool measured = last_ && last_->width == f.width && last_->height == f.height &&
                        last_->tileX == f.tileX && last_->tileY == f.tileY &&
                        last_->imageWidth == f.imageWidth && last_->imageHeight == f.imageHeight;
  const FrameSetup before = last_ ? *last_ : f;
  last_ = f;
  last_->timeline = {};
  if (cost_[0].size() != n) {
    for (DeviceBuffer<uint32_t>& c : cost_) c = DeviceBuffer<uint32_t>(n);
    keys_ = DeviceBuffer<uint32_t>(n);
    order_ = DeviceBuffer<uint32_t>(n);
  }
  std::swap(cost_[0], cost_[1]);  // [1]: the last frame's
  if (!measured) {
    fillDevice(cost_[0].data(), 0, cost_[0].bytes(), stream);
    return {nullptr, cost_[0].data()};
  }
  launchDependent(tileOrderKernel, 1, ORDER_THREADS, stream, f, before, cost_[1].data(),
                  cost_[0].data(), keys_.data(), order_.data(), n);
  return {order_.data(), cost_[0].data()};
}

}  // namespace gvdp::detail
