// renderRay (ray_tasks.h) for a whole warp whose lanes share their samples out
// (render/march_warp.cuh): sp's and graph's render passes, which launch whole warps.
#pragma once

#include "gvdp/render/march_warp.cuh"
#include "gvdp/sched/ray_tasks.h"

namespace gvdp::detail {

// renderRay's march of a warp's rays (every lane of the warp calls renderRay with it).
struct WarpRays {
  WarpMarchShared* shared;  // the warp's
  template <class Access>
  __device__ MarchResult operator()(const Ray& ray, const Lod& lod, RayState& s, Access& access,
                                    bool active) const {
    return marchWarp(ray, lod, s, access, active, *shared);
  }
};

}  // namespace gvdp::detail
