// Launcher of a pt frame's start (pt_kernels.cu); the worker kernel is launched through
// CudaProducerKernels (pt_worker.cuh).
#pragma once

#include <cuda_runtime_api.h>

#include "gvdp/sched/pt/pt_body.h"

namespace gvdp::detail {

// The frame's start in one launch: the ray and task rings emptied, the free task-id rings filled
// (pt_body.h: PtLayout), every ray's payload fresh (a pixel no ray reached resolves as
// unfinished), the counters at their start (initialPtCounter). It replaced a host copy of the
// counters, a memset and five ring launches, at the same frame times (floors x0.998, H100): pt's
// workers start 0.23 ms after sp's first pass (`timeline --again`) for another reason.
void launchPtFrameStart(const PtContext& ctx, const PtLayout& layout, cudaStream_t stream);

}  // namespace gvdp::detail
