#include "gvdp/base/parallel.h"
#include "gvdp/profile/frame_timeline.h"
#include "gvdp/profile/timeline_cpu.h"

namespace gvdp::detail {

const char* taskKindName(TaskKind k) {
  static const char* const NAMES[TASK_KIND_COUNT] = {"render", "production", "resolve",
                                                     "cache",  "sweep",      "prefetch"};
  return NAMES[static_cast<int>(k)];
}

namespace {
void observe(void* timeline, uint8_t kind, int worker, uint64_t start, uint64_t end) {
  static_cast<CpuTimeline*>(timeline)->view().push({start, end, static_cast<uint16_t>(worker),
                                                    static_cast<uint16_t>(worker),
                                                    static_cast<TaskKind>(kind)});
}
}  // namespace

void recordThreadPoolInto(CpuTimeline* timeline) {
  setTaskObserver(timeline ? TaskObserver{observe, timeline} : TaskObserver{});
}

}  // namespace gvdp::detail

namespace gvdp::detail {
namespace {

class CpuFrameTimeline final : public FrameTimeline {
 public:
  CpuFrameTimeline() : timeline_(TIMELINE_CAPACITY) {}
  TimelineView begin() override {
    timeline_.begin();
    recordThreadPoolInto(&timeline_);
    return {};  // CPU tasks record through the thread pool
  }
  TimelineCapture end() override {
    recordThreadPoolInto(nullptr);
    TimelineCapture c;
    c.records = timeline_.end(&c.overflow);
    c.lanes = ThreadPool::global().size();
    return c;
  }

 private:
  CpuTimeline timeline_;
};

}  // namespace

std::unique_ptr<FrameTimeline> makeCpuFrameTimeline() {
  return std::make_unique<CpuFrameTimeline>();
}

}  // namespace gvdp::detail
