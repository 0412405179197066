// Launchers of the CUDA sp kernels (sp_kernels.cu), on the scheduler's stream.
#pragma once

#include <cuda_runtime_api.h>

#include "gvdp/cache/cache_view.h"
#include "gvdp/render/brick_pool.h"
#include "gvdp/render/march.h"
#include "gvdp/sched/ray_tasks.h"
#include "gvdp/sched/tile_order.h"

namespace gvdp::detail {

// passCounters[0]: rays stopped in the pass (appended to `next`); [1]: unfinished at resolve.
// Rays that finish go to `finished` (ray_tasks.h). The first pass takes the tiles in `order` and
// measures their costs.
void launchFirstRenderPass(const FrameSetup& f, const CacheView& cache, const BrickPool& pool,
                           const TileOrder& order, RayState* payload, FinishedRays finished,
                           uint32_t* next, uint32_t* passCounters, cudaStream_t stream);
void launchRenderPass(const FrameSetup& f, const CacheView& cache, const BrickPool& pool,
                      RayState* payload, FinishedRays finished, const uint32_t* live,
                      uint32_t liveCount, uint32_t* next, uint32_t* passCounters,
                      cudaStream_t stream);
// Appends the pixels whose ray is not finished to `live`; passCounters[0] counts them.
void launchCompactUnfinished(const FrameSetup& f, const RayState* payload, uint32_t* live,
                             uint32_t* passCounters, cudaStream_t stream);
void launchResolve(const FrameSetup& f, const RayState* payload, uint32_t* image,
                   uint32_t* passCounters, cudaStream_t stream);

}  // namespace gvdp::detail
