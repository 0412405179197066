#include "gvdp/sched/scheduler.h"

#include <cstdlib>
#include <string>

#include "gvdp/base/error.h"
#include "gvdp/base/gpu.h"
#include "gvdp/sched/direct/direct.h"
#include "gvdp/sched/dp/dp.h"
#include "gvdp/sched/graph/graph.h"
#include "gvdp/sched/pt/pt.h"
#include "gvdp/sched/sp/sp.h"

namespace gvdp {

std::string_view backendName(Backend b) {
  return b == Backend::Cpu ? "cpu" : "cuda";
}

Backend parseBackend(std::string_view name) {
  if (name == "cpu") return Backend::Cpu;
  if (name == "cuda") return Backend::Cuda;
  throw InputError("unknown backend '" + std::string(name) + "' (backends: cpu, cuda)");
}

namespace {
constexpr std::string_view SCHEDULER_NAMES[] = {"direct", "sp", "dp", "pt", "graph"};
constexpr int SCHEDULER_COUNT = 5;
}  // namespace

std::string_view schedulerName(SchedulerKind k) {
  return SCHEDULER_NAMES[static_cast<int>(k)];
}

SchedulerKind parseScheduler(std::string_view name) {
  for (int k = 0; k < SCHEDULER_COUNT; ++k)
    if (SCHEDULER_NAMES[k] == name) return static_cast<SchedulerKind>(k);
  throw InputError("unknown scheduler '" + std::string(name) +
                   "' (schedulers: sp, dp, pt, graph, direct)");
}

void requireBackend(Backend backend) {
  if (backend != Backend::Cuda) return;
  GVDP_INPUT_CHECK(cudaBuilt(), "backend 'cuda' unavailable: this gvdp was built without CUDA");
  GVDP_INPUT_CHECK(cudaDeviceAvailable(), "backend 'cuda' unavailable: ", cudaDeviceSummary());
}

Scheduler::Scheduler(Backend backend)
    : clock_(backend == Backend::Cuda
                 ? makeGpuFrameClock()
                 : std::unique_ptr<FrameClock>(std::make_unique<CpuFrameClock>())) {}

Scheduler::~Scheduler() = default;

FrameStats Scheduler::render(const FrameSetup& frame, Image& out) {
  FrameStats stats;
  stats.index = frame.frameIndex;
  prepareFrame(frame);
  if (timeline_) timeline_->begin();
  clock_->start();
  renderFrame(frame, out, stats);
  stats.ms = clock_->stopMs();
  if (timeline_) stats.timeline = timeline_->end();
  finishFrame(frame, out, stats);
  return stats;
}

GraphDriver graphDriverFromEnvironment() {
  const char* v = std::getenv("GVDP_GRAPH_LOOP");
  std::string value = v ? v : "device";
  GVDP_INPUT_CHECK(value == "device" || value == "host", "bad GVDP_GRAPH_LOOP '", value,
                   "' (expected device or host)");
  return value == "host" ? GraphDriver::Host : GraphDriver::Device;
}

namespace {
std::unique_ptr<Scheduler> makeBare(const SchedulerOptions& options) {
  requireBackend(options.backend);
  if (options.backend == Backend::Cuda) {
    switch (options.kind) {
      case SchedulerKind::Direct:
        return makeDirectCuda();
      case SchedulerKind::Sp:
        return makeSpCuda(options);
      case SchedulerKind::Dp:
        return makeDpCuda(options);
      case SchedulerKind::Pt:
        return makePtCuda(options);
      case SchedulerKind::Graph:
        return makeGraphCuda(options);
    }
  }
  switch (options.kind) {
    case SchedulerKind::Direct:
      return makeDirectCpu();
    case SchedulerKind::Sp:
      return makeSpCpu(options);
    case SchedulerKind::Dp:
      return makeDpCpu(options);
    case SchedulerKind::Pt:
      return makePtCpu(options);
    case SchedulerKind::Graph:
      break;
  }
  throw InputError("scheduler 'graph' runs on the cuda backend only (a CUDA graph of the sp loop)");
}
}  // namespace

std::unique_ptr<Scheduler> makeScheduler(const SchedulerOptions& options) {
  std::unique_ptr<Scheduler> s = makeBare(options);
  if (options.timeline)
    s->recordTimeline(options.backend == Backend::Cuda ? makeGpuFrameTimeline()
                                                       : makeCpuFrameTimeline());
  return s;
}

}  // namespace gvdp
