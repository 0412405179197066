#include "gvdp/base/cuda_util.h"
#include "gvdp/sched/direct/direct.h"
#include "gvdp/sched/producer_kernels_cuda.h"

namespace gvdp::detail {
namespace {

class DirectCuda final : public Scheduler {
 public:
  explicit DirectCuda(ProducerKernelsPtr producer)
      : Scheduler(Backend::Cuda, std::move(producer)) {}
  MemoryReport memory() const override { return {}; }
  const uint32_t* deviceImage() const override { return image_.data(); }

 private:
  void prepareFrame(const FrameSetup& frame) override {
    size_t n = static_cast<size_t>(frame.pixelCount());
    if (image_.size() != n) image_ = DeviceBuffer<uint32_t>(n);
  }
  void renderFrame(const FrameSetup& frame, Image&, FrameStats&) override {
    cudaProducer().launchDirect(frame, image_.data(), stream());
    GVDP_CUDA_CHECK(cudaGetLastError());
  }
  void finishFrame(const FrameSetup& frame, Image& out, FrameStats&) override {
    if (!hostImageWanted()) return;
    out = Image(frame.width, frame.height);
    readDevice(out.pixels.data(), image_.data(), image_.bytes(), stream());
  }

  DeviceBuffer<uint32_t> image_;
};

}  // namespace

std::unique_ptr<Scheduler> makeDirectCuda(ProducerKernelsPtr producer) {
  return std::make_unique<DirectCuda>(std::move(producer));
}

}  // namespace gvdp::detail
