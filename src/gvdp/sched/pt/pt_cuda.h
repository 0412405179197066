// Launcher of a pt frame's start (pt_kernels.cu); the worker kernel is launched through
// CudaProducerKernels (pt_worker.cuh).
#pragma once

#include <cuda_runtime_api.h>

#include "gvdp/sched/pt/pt_context.h"

namespace gvdp::detail {

// The frame's start in one launch: the counters at their start (initialPtCounter); unless
// `keepRings` (the last frame left them quiet: ptRingsQuiet), the ray and task rings emptied and
// the free task-id rings filled (pt_context.h: PtLayout). No payload is written: a fresh ray starts
// from initialRayState (ptRunRay), and a pixel no ray reached keeps PT_LIVE_RAYS above 0, which
// the frame reports as unfinished pixels. *resolveCount = 0 (launchResolve's count, in the same
// launch: a memset between the worker and the resolve would keep the resolve from starting before
// the worker ends, base/dependent_launch.cuh).
void launchPtFrameStart(const PtContext& ctx, const PtLayout& layout, bool keepRings,
                        uint32_t* resolveCount, cudaStream_t stream);

}  // namespace gvdp::detail
