// The brick pool as seen by the ray march and by production, on both backends: slots of 10^3
// RGBA8 samples (8^3 voxels and a one-voxel border, so that filtering is seamless across brick
// edges), slot-major, read through the shared software trilinear().
//
// Why not a 3D texture with hardware filtering (paper 3.2): under dp and pt, bricks are written
// while other grids or blocks of the same frame read the pool, and the texture cache is coherent
// only at grid boundaries; a plain array read through L2 (ld.global.cg) is coherent, and every
// scheduler - and the CPU - then interpolates with the same arithmetic, bit for bit.
#pragma once

#include "gvdp/render/trilinear.h"

namespace gvdp::detail {

struct BrickPool {
  Rgba8* texels;  // slot * BRICK_SAMPLE_COUNT + (z * 10 + y) * 10 + x

  GVDP_HD static Rgba8 load(const Rgba8* p) {
#if GVDP_IS_GPU_CODE
    return __ldcg(p);
#else
    return *p;
#endif
  }

  // v: voxel coordinates of the brick's level (local); origin = 8 * local brick coordinates.
  GVDP_HD Vec4f sample(uint32_t slot, Vec3i origin, Vec3f v) const {
    const Rgba8* brick = texels + static_cast<size_t>(slot) * BRICK_SAMPLE_COUNT;
    return trilinear(v, [&](int x, int y, int z) {
      return load(brick +
                  ((z - origin.z + 1) * BRICK_SAMPLES + (y - origin.y + 1)) * BRICK_SAMPLES +
                  (x - origin.x + 1));
    });
  }

  GVDP_HD void write(uint32_t slot, int sample, Rgba8 value) const {
    texels[static_cast<size_t>(slot) * BRICK_SAMPLE_COUNT + sample] = value;
  }
};

}  // namespace gvdp::detail
