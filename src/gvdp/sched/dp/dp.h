// The `dp` scheduler (the paper): render and production tasks launch each other on the device
// (CUDA Dynamic Parallelism; a task queue on the CPU). See dp_body.h for the protocol. Rays a
// device-side schedule could not finish (refused launch, launch depth limit) are finished by
// the sp loop afterwards, and counted.
#pragma once

#include <cstddef>
#include <memory>

#include "gvdp/sched/scheduler.h"

namespace gvdp::detail {

std::unique_ptr<Scheduler> makeDpCpu(const SchedulerOptions& options, ProducerKernelsPtr producer);
std::unique_ptr<Scheduler> makeDpCuda(const SchedulerOptions& options, ProducerKernelsPtr producer);
// Bytes of the CPU task queue at full capacity (its memory() item "task_queue").
size_t dpCpuTaskQueueBytes(size_t pendingLaunches);

}  // namespace gvdp::detail
