#include "gvdp/base/parallel.h"
#include "gvdp/render/direct.h"
#include "gvdp/sched/direct/direct.h"

namespace gvdp {
namespace {

class DirectCpu final : public Scheduler {
 public:
  DirectCpu() : Scheduler(Backend::Cpu) {}
  MemoryReport memory() const override { return {}; }

 private:
  void renderFrame(const FrameSetup& frame, Image& out, FrameStats&) override {
    out = Image(frame.width, frame.height);
    uint32_t* pixels = out.pixels.data();
    parallelFor(
        frame.pixelCount(),
        [&](int64_t i) { pixels[i] = renderDirectPixel(frame, static_cast<int>(i)); }, 16);
  }
};

}  // namespace

std::unique_ptr<Scheduler> makeDirectCpu() {
  return std::make_unique<DirectCpu>();
}

}  // namespace gvdp
