// Stand-ins for the CUDA schedulers in builds without CUDA (GVDP_CUDA=OFF); makeScheduler
// refuses the cuda backend before reaching them.
#include "gvdp/base/error.h"
#include "gvdp/profile/frame_clock.h"
#include "gvdp/sched/direct/direct.h"
#include "gvdp/sched/dp/dp.h"
#include "gvdp/sched/graph/graph.h"
#include "gvdp/sched/importance_map.h"
#include "gvdp/sched/pt/pt.h"
#include "gvdp/sched/sp/sp.h"

namespace gvdp::detail {

std::unique_ptr<Scheduler> makeDirectCuda(ProducerKernelsPtr) {
  throw InputError("backend 'cuda' unavailable: this gvdp was built without CUDA");
}

std::unique_ptr<Scheduler> makeSpCuda(const SchedulerOptions&, ProducerKernelsPtr) {
  throw InputError("backend 'cuda' unavailable: this gvdp was built without CUDA");
}

std::unique_ptr<Scheduler> makeDpCuda(const SchedulerOptions&, ProducerKernelsPtr) {
  throw InputError("backend 'cuda' unavailable: this gvdp was built without CUDA");
}

std::unique_ptr<Scheduler> makePtCuda(const SchedulerOptions&, ProducerKernelsPtr) {
  throw InputError("backend 'cuda' unavailable: this gvdp was built without CUDA");
}

std::unique_ptr<Scheduler> makeGraphCuda(const SchedulerOptions&, ProducerKernelsPtr) {
  throw InputError("backend 'cuda' unavailable: this gvdp was built without CUDA");
}

ImportanceStatus countBricksOnDevice(const ProducerKernels&, const FrameSetup&, uint64_t, GpuStream,
                                     ImportanceMap&) {
  throw InputError("backend 'cuda' unavailable: this gvdp was built without CUDA");
}

std::unique_ptr<FrameClock> makeGpuFrameClock(GpuStream) {
  throw InputError("backend 'cuda' unavailable: this gvdp was built without CUDA");
}

std::unique_ptr<FrameTimeline> makeGpuFrameTimeline(GpuStream) {
  throw InputError("backend 'cuda' unavailable: this gvdp was built without CUDA");
}

}  // namespace gvdp::detail
