// The GPU-cores timeline (paper 4.3, Figure 5): one record per instrumented block (GPU) or per
// task and worker thread (CPU): its task kind, the SM (or worker) it ran on, start and end in
// nanoseconds. Records go to a preallocated buffer through an atomic index; records past the
// capacity are counted, never written.
#pragma once

#include <cstdint>

#include "gvdp/base/atomics.h"
#include "gvdp/base/defs.h"

namespace gvdp::detail {

enum class TaskKind : uint8_t { Render, Produce, Resolve, Cache, Sweep, Prefetch };
constexpr int TASK_KIND_COUNT = 6;
const char* taskKindName(TaskKind k);

struct TimelineRecord {
  uint64_t start, end;      // ns (%globaltimer on the GPU, steady_clock on the CPU)
  uint16_t smStart, smEnd;  // SM (or worker) at start and at end (a block never migrates)
  TaskKind kind;
};

struct TimelineView {
  TimelineRecord* records;  // nullptr: profiling off
  uint32_t capacity;
  uint32_t* count;  // [0] records claimed (may exceed capacity: the excess is the overflow)

  GVDP_HD bool enabled() const { return records != nullptr; }
  GVDP_HD void push(const TimelineRecord& r) const {
    uint32_t i = atomicAdd32(count, 1u);
    if (i < capacity) records[i] = r;
  }
};

}  // namespace gvdp::detail
