#include "gvdp/sched/direct/direct_cuda.h"

#include "gvdp/base/cuda_util.h"
#include "gvdp/sched/direct/direct.h"

namespace gvdp {
namespace {

class DirectCuda final : public Scheduler {
 public:
  FrameStats render(const FrameSetup& frame, Image& out) override {
    size_t n = static_cast<size_t>(frame.pixelCount());
    if (image_.size() != n) image_ = DeviceBuffer<uint32_t>(n);
    timelineBegin();
    timer_.start();
    launchDirect(frame, image_.data(), nullptr);
    GVDP_CUDA_CHECK(cudaGetLastError());
    timer_.stop();
    FrameStats s;
    s.index = frame.frameIndex;
    s.ms = timer_.ms();
    timelineEnd(s);
    out = Image(frame.width, frame.height);
    GVDP_CUDA_CHECK(cudaMemcpy(out.pixels.data(), image_.data(), n * 4, cudaMemcpyDeviceToHost));
    return s;
  }

  MemoryReport memory() const override { return {}; }

 private:
  DeviceBuffer<uint32_t> image_;
  GpuTimer timer_;
};

}  // namespace

std::unique_ptr<Scheduler> makeDirectCuda() {
  return std::make_unique<DirectCuda>();
}

}  // namespace gvdp
