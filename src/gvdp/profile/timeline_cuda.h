// Host side of the CUDA timeline: a preallocated device buffer, switched on for one frame.
#pragma once

#include <vector>

#include "gvdp/base/cuda_util.h"
#include "gvdp/profile/timeline.h"

namespace gvdp::detail {

class GpuTimeline {
 public:
  GpuTimeline(uint32_t capacity, cudaStream_t stream)
      : records_(capacity), count_(1), stream_(stream) {}

  // The view kernels record into (FrameSetup::timeline), emptied.
  TimelineView begin() {
    fillDevice(count_.data(), 0, sizeof(uint32_t), stream_);
    return {records_.data(), static_cast<uint32_t>(records_.size()), count_.data()};
  }
  // The records of the frame; `overflow` gets the records not kept.
  std::vector<TimelineRecord> end(uint64_t* overflow) {
    uint32_t n = 0;
    readDevice(&n, count_.data(), sizeof n, stream_);
    uint32_t kept = n < records_.size() ? n : static_cast<uint32_t>(records_.size());
    *overflow = n - kept;
    std::vector<TimelineRecord> out(kept);
    readDevice(out.data(), records_.data(), kept * sizeof(TimelineRecord), stream_);
    return out;
  }

 private:
  DeviceBuffer<TimelineRecord> records_;
  DeviceBuffer<uint32_t> count_;
  cudaStream_t stream_;
};

}  // namespace gvdp::detail
