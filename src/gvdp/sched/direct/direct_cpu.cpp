#include <chrono>

#include "gvdp/base/parallel.h"
#include "gvdp/render/direct.h"
#include "gvdp/sched/direct/direct.h"

namespace gvdp {
namespace {

class DirectCpu final : public Scheduler {
 public:
  FrameStats render(const FrameSetup& frame, Image& out) override {
    timelineBegin();
    auto t0 = std::chrono::steady_clock::now();
    out = Image(frame.width, frame.height);
    uint32_t* pixels = out.pixels.data();
    parallelFor(
        frame.pixelCount(),
        [&](int64_t i) { pixels[i] = renderDirectPixel(frame, static_cast<int>(i)); }, 16);
    FrameStats s;
    s.index = frame.frameIndex;
    s.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    timelineEnd(s);
    return s;
  }

  MemoryReport memory() const override { return {}; }
};

}  // namespace

std::unique_ptr<Scheduler> makeDirectCpu() {
  return std::make_unique<DirectCpu>();
}

}  // namespace gvdp
