#include "gvdp/sched/scheduler.h"

#include <cstdlib>
#include <string>

#include "gvdp/base/error.h"
#include "gvdp/base/gpu.h"
#include "gvdp/mesh/text_tokens.h"
#include "gvdp/sched/direct/direct.h"
#include "gvdp/sched/dp/dp.h"
#include "gvdp/sched/graph/graph.h"
#include "gvdp/sched/pt/pt.h"
#include "gvdp/sched/sp/sp.h"

namespace gvdp::detail {

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

Scheduler::Scheduler(Backend backend, ProducerKernelsPtr producer)
    : producer_(std::move(producer)),
      backend_(backend),
      stream_(backend == Backend::Cuda ? createGpuStream() : nullptr),
      clock_(backend == Backend::Cuda
                 ? makeGpuFrameClock(stream_.get())
                 : std::unique_ptr<FrameClock>(std::make_unique<CpuFrameClock>())) {}

Scheduler::~Scheduler() = default;

FrameStats Scheduler::render(const FrameSetup& frame, Image* target) {
  GVDP_INPUT_CHECK(target || backend_ == Backend::Cuda,
                   "an image in device memory needs the cuda backend");
  hostImage_ = target != nullptr;
  Image scratch;
  Image& out = target ? *target : scratch;
  FrameStats stats;
  stats.index = frame.frameIndex;
  prepareFrame(frame);
  FrameSetup f = frame;
  if (timeline_) f.timeline = timeline_->begin();
  f.rayCosts = rayCosts_;
  clock_->start();
  renderFrame(f, out, stats);
  stats.ms = clock_->stopMs();
  if (timeline_) stats.timeline = timeline_->end();
  finishFrame(f, out, stats);
  return stats;
}

GraphDriver graphDriverFromEnvironment() {
  const char* v = std::getenv("GVDP_GRAPH_LOOP");
  std::string value = v ? v : "device";
  GVDP_INPUT_CHECK(value == "device" || value == "host", "bad GVDP_GRAPH_LOOP '", value,
                   "' (expected device or host)");
  return value == "host" ? GraphDriver::Host : GraphDriver::Device;
}

uint32_t ptProducerShareFromEnvironment() {
  const char* v = std::getenv("GVDP_PT_PRODUCER_SHARE");
  if (v == nullptr || *v == '\0') return PT_PRODUCER_SHARE_DEFAULT;
  int64_t s = 0;
  GVDP_INPUT_CHECK(parseInt(v, s) && s >= 0 && s <= 4096, "bad GVDP_PT_PRODUCER_SHARE '", v,
                   "' (expected 0..4096; 0: off)");
  return static_cast<uint32_t>(s);
}

namespace {
std::unique_ptr<Scheduler> makeBare(const SchedulerOptions& options, ProducerKernelsPtr p) {
  requireBackend(options.backend);
  if (options.backend == Backend::Cuda) {
    GVDP_INPUT_CHECK(p->cuda(),
                     "backend 'cuda' needs the producer compiled by nvcc: build the "
                     "translation unit that calls makeRenderer as CUDA");
    switch (options.kind) {
      case SchedulerKind::Direct:
        return makeDirectCuda(std::move(p));
      case SchedulerKind::Sp:
        return makeSpCuda(options, std::move(p));
      case SchedulerKind::Dp:
        return makeDpCuda(options, std::move(p));
      case SchedulerKind::Pt:
        return makePtCuda(options, std::move(p));
      case SchedulerKind::Graph:
        return makeGraphCuda(options, std::move(p));
    }
  }
  switch (options.kind) {
    case SchedulerKind::Direct:
      return makeDirectCpu(std::move(p));
    case SchedulerKind::Sp:
      return makeSpCpu(options, std::move(p));
    case SchedulerKind::Dp:
      return makeDpCpu(options, std::move(p));
    case SchedulerKind::Pt:
      return makePtCpu(options, std::move(p));
    case SchedulerKind::Graph:
      break;
  }
  throw InputError("scheduler 'graph' runs on the cuda backend only (a CUDA graph of the sp loop)");
}
}  // namespace

void recordTimelineOf(Scheduler& s, Backend backend, bool on) {
  if (!on)
    s.recordTimeline(nullptr);
  else
    s.recordTimeline(backend == Backend::Cuda ? makeGpuFrameTimeline(s.stream())
                                              : makeCpuFrameTimeline());
}

std::unique_ptr<Scheduler> makeScheduler(const SchedulerOptions& options,
                                         ProducerKernelsPtr producer) {
  std::unique_ptr<Scheduler> s = makeBare(options, std::move(producer));
  if (options.timeline) recordTimelineOf(*s, options.backend, true);
  s->recordRayCosts(options.rayCosts);
  return s;
}

}  // namespace gvdp::detail
