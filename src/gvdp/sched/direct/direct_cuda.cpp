#include "gvdp/sched/direct/direct_cuda.h"

#include "gvdp/base/cuda_util.h"
#include "gvdp/sched/direct/direct.h"

namespace gvdp {
namespace {

class DirectCuda final : public Scheduler {
 public:
  DirectCuda() : Scheduler(Backend::Cuda) {}
  MemoryReport memory() const override { return {}; }

 private:
  void prepareFrame(const FrameSetup& frame) override {
    size_t n = static_cast<size_t>(frame.pixelCount());
    if (image_.size() != n) image_ = DeviceBuffer<uint32_t>(n);
  }
  void renderFrame(const FrameSetup& frame, Image&, FrameStats&) override {
    launchDirect(frame, image_.data(), nullptr);
    GVDP_CUDA_CHECK(cudaGetLastError());
  }
  void finishFrame(const FrameSetup& frame, Image& out, FrameStats&) override {
    out = Image(frame.width, frame.height);
    GVDP_CUDA_CHECK(
        cudaMemcpy(out.pixels.data(), image_.data(), image_.bytes(), cudaMemcpyDeviceToHost));
  }

  DeviceBuffer<uint32_t> image_;
};

}  // namespace

std::unique_ptr<Scheduler> makeDirectCuda() {
  return std::make_unique<DirectCuda>();
}

}  // namespace gvdp
