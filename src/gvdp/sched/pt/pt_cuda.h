// Launchers of the CUDA pt kernels (pt_kernels.cu).
#pragma once

#include "gvdp/render/brick_pool.h"
#include "gvdp/sched/pt/pt_body.h"

namespace gvdp {

// Worker blocks of the persistent kernel: as many as fit on the device at once.
int ptWorkerBlocks();
// Empties the ray and task rings and fills the free task-id ring with ids 0..ids-1.
void launchPtRingsInit(const PtContext& ctx, uint32_t ids);
// The frame's persistent kernel: returns (to the stream) when every ray has finished.
void launchPtFrame(const PtContext& ctx, const BrickPool& pool, int blocks);

}  // namespace gvdp
