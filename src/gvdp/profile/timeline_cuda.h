// Host side of the CUDA timeline: a preallocated device buffer, switched on for one frame.
#pragma once

#include <vector>

#include "gvdp/base/cuda_util.h"
#include "gvdp/profile/timeline.h"

namespace gvdp::detail {

class GpuTimeline {
 public:
  explicit GpuTimeline(uint32_t capacity) : records_(capacity), count_(1) {}

  // The view kernels record into (FrameSetup::timeline), emptied.
  TimelineView begin() {
    GVDP_CUDA_CHECK(cudaMemset(count_.data(), 0, sizeof(uint32_t)));
    return {records_.data(), static_cast<uint32_t>(records_.size()), count_.data()};
  }
  // The records of the frame; `overflow` gets the records not kept.
  std::vector<TimelineRecord> end(uint64_t* overflow) {
    uint32_t n = 0;
    GVDP_CUDA_CHECK(cudaMemcpy(&n, count_.data(), sizeof n, cudaMemcpyDeviceToHost));
    uint32_t kept = n < records_.size() ? n : static_cast<uint32_t>(records_.size());
    *overflow = n - kept;
    std::vector<TimelineRecord> out(kept);
    GVDP_CUDA_CHECK(cudaMemcpy(out.data(), records_.data(), kept * sizeof(TimelineRecord),
                               cudaMemcpyDeviceToHost));
    return out;
  }

 private:
  DeviceBuffer<TimelineRecord> records_;
  DeviceBuffer<uint32_t> count_;
};

}  // namespace gvdp::detail
