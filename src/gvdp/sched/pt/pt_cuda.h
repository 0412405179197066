// Launcher of a pt frame's start (pt_kernels.cu); the worker kernel is launched through
// CudaProducerKernels (pt_worker.cuh).
#pragma once

#include <cuda_runtime_api.h>

#include "gvdp/sched/pt/pt_body.h"

namespace gvdp::detail {

// The frame's start in one launch: the ray and task rings emptied, the free task-id rings filled
// (pt_body.h: PtLayout), every ray's payload fresh (a pixel no ray reached resolves as
// unfinished), the counters at their start (initialPtCounter). Once a host copy of the counters
// and six launches: 0.23 ms more than sp before the first ray (`timeline --again`, H100).
void launchPtFrameStart(const PtContext& ctx, const PtLayout& layout, cudaStream_t stream);

}  // namespace gvdp::detail
