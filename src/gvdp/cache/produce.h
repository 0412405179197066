// The body of the production task (paper Algorithm 2): one producer evaluation per sample of a
// brick, 10^3 samples = 8^3 voxels and a one-voxel border, at the voxel centres of the brick's
// level. The caller ANDs the empty flags over the brick, takes a slot, writes the samples and
// publishes the entry (cache_ops.h).
#pragma once

#include "gvdp/cache/brick_key.h"
#include "gvdp/world/scene.h"

namespace gvdp {

GVDP_HD GVDP_INLINE Vec3i brickSampleIndex(int sample) {
  return {sample % BRICK_SAMPLES, (sample / BRICK_SAMPLES) % BRICK_SAMPLES,
          sample / (BRICK_SAMPLES * BRICK_SAMPLES)};
}

// World position of a sample's voxel centre. Exact in double (voxel sizes are powers of two),
// hence equal to the direct renderer's localOrigin + (i + 1/2) v.
GVDP_HD GVDP_INLINE Vec3d brickSampleCentre(const BrickKey& key, int sample, float voxelSize0) {
  double vs = ldexp(static_cast<double>(voxelSize0), key.level);
  Vec3i i = brickSampleIndex(sample);
  auto centre = [&](int brick, int index) {
    long long voxel = static_cast<long long>(brick) * BRICK_WIDTH + index - 1;
    return (static_cast<double>(voxel) + 0.5) * vs;
  };
  return {centre(key.brick.x, i.x), centre(key.brick.y, i.y), centre(key.brick.z, i.z)};
}

GVDP_HD GVDP_INLINE VoxelSample produceBrickSample(const SceneParams& scene, const BrickKey& key,
                                                   int sample) {
  float vs = ldexpf(scene.voxelSize0, key.level);
  return produceVoxel(scene, brickSampleCentre(key, sample, scene.voxelSize0), vs);
}

}  // namespace gvdp
