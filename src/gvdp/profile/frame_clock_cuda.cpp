#include "gvdp/base/cuda_util.h"
#include "gvdp/profile/frame_clock.h"

namespace gvdp::detail {
namespace {

class GpuFrameClock final : public FrameClock {
 public:
  explicit GpuFrameClock(cudaStream_t stream) : stream_(stream) {}
  void start() override { timer_.start(stream_); }
  double stopMs() override {
    timer_.stop(stream_);
    return timer_.ms();
  }

 private:
  cudaStream_t stream_;
  GpuTimer timer_;
};

}  // namespace

std::unique_ptr<FrameClock> makeGpuFrameClock(GpuStream stream) {
  return std::make_unique<GpuFrameClock>(stream);
}

}  // namespace gvdp::detail
