#include "gvdp/sched/scheduler.h"

#include "gvdp/base/error.h"
#include "gvdp/base/gpu.h"
#include "gvdp/sched/direct.h"
#include "gvdp/sched/sp.h"

namespace gvdp {

std::string_view backendName(Backend b) {
  return b == Backend::Cpu ? "cpu" : "cuda";
}

Backend parseBackend(std::string_view name) {
  if (name == "cpu") return Backend::Cpu;
  if (name == "cuda") return Backend::Cuda;
  throw InputError("unknown backend '" + std::string(name) + "' (backends: cpu, cuda)");
}

std::string_view schedulerName(SchedulerKind k) {
  return k == SchedulerKind::Direct ? "direct" : "sp";
}

SchedulerKind parseScheduler(std::string_view name) {
  if (name == "direct") return SchedulerKind::Direct;
  if (name == "sp") return SchedulerKind::Sp;
  throw InputError("unknown scheduler '" + std::string(name) + "' (schedulers: sp, direct)");
}

std::unique_ptr<Scheduler> makeScheduler(const SchedulerOptions& options) {
  if (options.backend == Backend::Cuda) {
    GVDP_INPUT_CHECK(cudaBuilt(), "backend 'cuda' unavailable: this gvdp was built without CUDA");
    GVDP_INPUT_CHECK(cudaDeviceAvailable(), "backend 'cuda' unavailable: ", cudaDeviceSummary());
    return options.kind == SchedulerKind::Direct ? makeDirectCuda() : makeSpCuda(options);
  }
  return options.kind == SchedulerKind::Direct ? makeDirectCpu() : makeSpCpu(options);
}

}  // namespace gvdp
