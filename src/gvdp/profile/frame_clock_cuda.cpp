#include "gvdp/base/cuda_util.h"
#include "gvdp/profile/frame_clock.h"

namespace gvdp::detail {
namespace {

class GpuFrameClock final : public FrameClock {
 public:
  void start() override { timer_.start(); }
  double stopMs() override {
    timer_.stop();
    return timer_.ms();
  }

 private:
  GpuTimer timer_;
};

}  // namespace

std::unique_ptr<FrameClock> makeGpuFrameClock() {
  return std::make_unique<GpuFrameClock>();
}

}  // namespace gvdp::detail
