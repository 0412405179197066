// The tile order (tile_order.h) on the CUDA backend: the block costs the last frame measured, moved
// with the camera's turn (reprojectedBlock) and sorted most costly first, for the next frame of the
// same size (a stable counting sort in one launch: blocks of equal cost stay in row-major order).
#pragma once

#include <cuda_runtime_api.h>

#include <optional>

#include "gvdp/base/cuda_util.h"
#include "gvdp/sched/tile_order.h"

namespace gvdp::detail {

class TileOrderCuda {
 public:
  // Frame f's order, queued on `stream`: by the costs of the last frame if it had f's pixels, else
  // row-major; and f's costs zeroed for it to measure.
  TileOrder next(const FrameSetup& f, cudaStream_t stream);
  size_t bytes() const {
    return cost_[0].bytes() + cost_[1].bytes() + keys_.bytes() + order_.bytes();
  }

 private:
  DeviceBuffer<uint32_t> cost_[2], keys_, order_;
  std::optional<FrameSetup> last_;  // the frame that measured cost_[1]
};

}  // namespace gvdp::detail
