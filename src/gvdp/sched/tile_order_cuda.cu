#include <cub/device/device_radix_sort.cuh>
#include <utility>

#include "gvdp/profile/parallel_for.cuh"
#include "gvdp/sched/tile_order_cuda.h"

namespace gvdp::detail {

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
    sortedKeys_ = DeviceBuffer<uint32_t>(n);
    blocks_ = DeviceBuffer<uint32_t>(n);
    order_ = DeviceBuffer<uint32_t>(n);
    size_t bytes = 0;
    GVDP_CUDA_CHECK(cub::DeviceRadixSort::SortPairsDescending(
        nullptr, bytes, keys_.data(), sortedKeys_.data(), blocks_.data(), order_.data(), n));
    temp_ = DeviceBuffer<uint8_t>(bytes);
  }
  std::swap(cost_[0], cost_[1]);  // [1]: the last frame's
  fillDevice(cost_[0].data(), 0, cost_[0].bytes(), stream);
  if (!measured) return {nullptr, cost_[0].data()};
  const uint32_t* cost = cost_[1].data();
  uint32_t *keys = keys_.data(), *blocks = blocks_.data();
  parallelForCuda("tile order: keys", stream, n, f.timeline, TaskKind::Cache,
                  [=] __device__(uint32_t i) {
                    int r = reprojectedBlock(f, before, static_cast<int>(i));
                    keys[i] = blockCostKey(neighbourhoodCost(cost, before, r));
                    blocks[i] = i;
                  });
  size_t bytes = temp_.bytes();
  GVDP_CUDA_CHECK(cub::DeviceRadixSort::SortPairsDescending(
      temp_.data(), bytes, keys, sortedKeys_.data(), blocks, order_.data(), n, 0, 8, stream));
  return {order_.data(), cost_[0].data()};
}

}  // namespace gvdp::detail
