// renderRay (ray_tasks.h) for a whole warp whose lanes share their samples out
// (render/march_warp.cuh): sp's and graph's render passes, which launch whole warps.
#pragma once

#include "gvdp/render/march_warp.cuh"
#include "gvdp/sched/ray_tasks.h"

namespace gvdp::detail {

// Every lane of the warp calls it; a lane with pixel < 0 has no ray. True when the lane's ray
// stopped on a missing brick (its state saved, to be relaunched after production).
template <class Pool>
__device__ bool renderRayWarp(const FrameSetup& f, const CacheView& cache, const Pool& pool,
                              RayState* payload, int pixel, WarpMarchShared& shared) {
  bool active = pixel >= 0;
  Ray ray = f.primaryRay(active ? pixel % f.width : 0, active ? pixel / f.width : 0);
  RayState s = active ? payload[pixel] : initialRayState();
  CachedAccess<Pool, QueueRequest, PoolReads::ReadOnly> access{cache, pool, f.lod};
  bool stopped = marchWarp(ray, f.lod, s, access, active, shared) == MarchResult::Stopped;
  access.addCounts();
  if (active) payload[pixel] = s;
  return stopped;
}

}  // namespace gvdp::detail
