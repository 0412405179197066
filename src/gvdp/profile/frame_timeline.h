// One frame's timeline capture for a scheduler, on either backend: begin before the frame's
// work, end after it (the records, their lanes and the overflow go to FrameStats).
#pragma once

#include <memory>
#include <vector>

#include "gvdp/base/gpu.h"
#include "gvdp/profile/timeline.h"

namespace gvdp::detail {

struct TimelineCapture {
  std::vector<TimelineRecord> records;
  int lanes = 0;
  uint64_t overflow = 0;
};

class FrameTimeline {
 public:
  virtual ~FrameTimeline() = default;
  // Starts a capture; the view is where GPU kernels record (CPU: an empty view).
  virtual TimelineView begin() = 0;
  virtual TimelineCapture end() = 0;
};

constexpr uint32_t TIMELINE_CAPACITY = 1u << 22;  // records per frame (about 100 MB on the GPU)

std::unique_ptr<FrameTimeline> makeCpuFrameTimeline();
// Records kernels write on the device, read back on `stream` (CUDA builds only).
std::unique_ptr<FrameTimeline> makeGpuFrameTimeline(GpuStream stream);

}  // namespace gvdp::detail
