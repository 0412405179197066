#include "gvdp/sched/direct/direct.h"

namespace gvdp::detail {
namespace {

class DirectCpu final : public Scheduler {
 public:
  explicit DirectCpu(ProducerKernelsPtr producer) : Scheduler(Backend::Cpu, std::move(producer)) {}
  MemoryReport memory() const override { return {}; }

 private:
  void renderFrame(const FrameSetup& frame, Image& out, FrameStats&) override {
    out = Image(frame.width, frame.height);
    producer().renderDirect(frame, out.pixels.data());
  }
};

}  // namespace

std::unique_ptr<Scheduler> makeDirectCpu(ProducerKernelsPtr producer) {
  return std::make_unique<DirectCpu>(std::move(producer));
}

}  // namespace gvdp::detail
