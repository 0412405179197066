// The CUDA brick pool's sampler: slots tiled in a 3D texture atlas (RGBA8, hardware trilinear
// filtering, paper 3.2); the one-voxel border of every slot makes the filtering seamless.
#pragma once

#include <cuda_runtime_api.h>

#include "gvdp/base/vecmath.h"
#include "gvdp/world/voxel.h"

namespace gvdp {

struct GpuPool {
  cudaTextureObject_t texture;  // read: normalised float, linear filtering, texel coordinates
  cudaSurfaceObject_t surface;  // write
  int slotsX, slotsY;           // atlas layout in slots (z follows)

  GVDP_HD Vec3i slotTexelOrigin(uint32_t slot) const {
    int sx = static_cast<int>(slot % static_cast<uint32_t>(slotsX));
    int sy =
        static_cast<int>((slot / static_cast<uint32_t>(slotsX)) % static_cast<uint32_t>(slotsY));
    int sz = static_cast<int>(slot / static_cast<uint32_t>(slotsX * slotsY));
    return {sx * BRICK_SAMPLES, sy * BRICK_SAMPLES, sz * BRICK_SAMPLES};
  }

#if defined(__CUDACC__)
  __device__ Vec4f sample(uint32_t slot, Vec3i origin, Vec3f v) const {
    Vec3i base = slotTexelOrigin(slot);
    // Sample j of the brick (j = -1..8) is texel base + j + 1, centred at v = origin + j + 1/2.
    float4 c = tex3D<float4>(texture, static_cast<float>(base.x + 1 - origin.x) + v.x,
                             static_cast<float>(base.y + 1 - origin.y) + v.y,
                             static_cast<float>(base.z + 1 - origin.z) + v.z);
    return {c.x, c.y, c.z, c.w};
  }
  __device__ void write(uint32_t slot, int sample, Rgba8 value) const {
    Vec3i base = slotTexelOrigin(slot);
    int x = sample % BRICK_SAMPLES, y = (sample / BRICK_SAMPLES) % BRICK_SAMPLES;
    int z = sample / (BRICK_SAMPLES * BRICK_SAMPLES);
    surf3Dwrite(value, surface, (base.x + x) * 4, base.y + y, base.z + z);
  }
#endif
};

}  // namespace gvdp
