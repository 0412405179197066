// renderRay (ray_tasks.h) for a whole warp whose lanes share their samples out
// (render/march_warp.cuh): sp's and graph's render passes, which launch whole warps.
#pragma once

#include "gvdp/render/march_warp.cuh"
#include "gvdp/sched/ray_tasks.h"

namespace gvdp::detail {

// The launch shape of render kernels that march with WarpRays (sp's and graph's): blocks of 4
// warps, 8 of them an SM at 64 registers (`__launch_bounds__(RENDER_BLOCK, RENDER_BLOCKS_PER_SM)`:
// 32 bytes of spills; unbounded at 83 registers, 24 warps an SM, x0.94 slower; one-warp blocks
// x1.03; BENCHMARKS.md, sessions 18 and 19), and each warp's shared memory for the march.
constexpr int RENDER_BLOCK = 128, RENDER_BLOCKS_PER_SM = 8;
constexpr int RENDER_BLOCK_WARPS = RENDER_BLOCK / WARP_SIZE;

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
