#include "gvdp/profile/timeline_cuda.h"
#include "gvdp/profile/frame_timeline.h"

namespace gvdp::detail {
namespace {

class GpuFrameTimeline final : public FrameTimeline {
 public:
  explicit GpuFrameTimeline(cudaStream_t stream)
      : timeline_(TIMELINE_CAPACITY, stream), lanes_(smCount()) {}
  TimelineView begin() override { return timeline_.begin(); }
  TimelineCapture end() override {
    TimelineCapture c;
    c.records = timeline_.end(&c.overflow);
    c.lanes = lanes_;
    return c;
  }

 private:
  GpuTimeline timeline_;
  int lanes_ = 0;
};

}  // namespace

std::unique_ptr<FrameTimeline> makeGpuFrameTimeline(GpuStream stream) {
  return std::make_unique<GpuFrameTimeline>(stream);
}

}  // namespace gvdp::detail
