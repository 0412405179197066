// Launchers of the CUDA dp kernels (dp_kernels.cu).
#pragma once

#include "gvdp/render/brick_pool.h"
#include "gvdp/sched/dp/dp_body.h"

namespace gvdp {

// Kernels nest at most this deep (CUDA's launch nesting limit is 24); a production that would
// go deeper is queued for the host's sweep instead (counted as DP_DEFERRED).
constexpr int DP_MAX_DEPTH = 23;

// Copies the frame's context to the device and launches the root render grid (32x16 tiles);
// the whole tree of device launches has finished when the stream reaches the next command.
void launchDpFrame(const DpContext& ctx, const BrickPool& pool);

}  // namespace gvdp
