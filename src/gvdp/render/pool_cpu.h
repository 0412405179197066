// The CPU brick pool's sampler: slots of 10^3 RGBA8 samples in one array (slot-major; the GPU
// atlas tiles the same slots in a 3D texture), read through the shared software trilinear().
#pragma once

#include "gvdp/render/trilinear.h"

namespace gvdp {

struct CpuPool {
  const Rgba8* texels;  // slot * BRICK_SAMPLE_COUNT + (z * 10 + y) * 10 + x

  GVDP_HD Vec4f sample(uint32_t slot, Vec3i origin, Vec3f v) const {
    const Rgba8* brick = texels + static_cast<size_t>(slot) * BRICK_SAMPLE_COUNT;
    return trilinear(v, [&](int x, int y, int z) {
      return brick[((z - origin.z + 1) * BRICK_SAMPLES + (y - origin.y + 1)) * BRICK_SAMPLES +
                   (x - origin.x + 1)];
    });
  }
};

}  // namespace gvdp
