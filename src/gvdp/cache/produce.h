// The production task (paper Algorithm 2), written once for every cooperation scope
// (base/cooperation.h): one producer evaluation per sample of a brick, 10^3 samples = 8^3 voxels
// and a one-voxel border, at the voxel centres of the brick's level; the group ANDs the empty
// flags, takes a slot, writes the samples and publishes the entry (cache_ops.h). A CPU task runs
// it as a ThreadScope, sp/dp/graph's production kernels as a BlockScope, pt as a WarpScope whose
// samples idle warps of the block help compute (pt_kernels.cu: produceChunks, then commitBrick).
#pragma once

#include "gvdp/base/cooperation.h"
#include "gvdp/cache/brick_key.h"
#include "gvdp/cache/cache_ops.h"
#include "gvdp/render/brick_pool.h"
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

// Algorithm 2's end, by a group whose member r holds the samples r + k * size (k < PER, with
// PER * size >= BRICK_SAMPLE_COUNT): the leader takes a slot (none for an empty brick), each
// member writes its samples staged(k, sample) to it and fences (device scope: other blocks
// read the pool), and the leader publishes the entry once every member's writes are fenced.
template <int PER, class Scope, class Staged>
GVDP_HD GVDP_INLINE void commitBrick(const Scope& group, const CacheView& cache,
                                     const BrickPool& pool, const BrickKey& key, bool empty,
                                     Staged staged) {
  uint32_t slot = 0;
  if (group.rank() == 0) slot = empty ? MAX_SLOTS : takeFreeSlot(cache);
  slot = group.broadcast(slot);
  if (!empty && slot != MAX_SLOTS) {
    GVDP_UNROLL
    for (int k = 0; k < PER; ++k) {
      int s = group.rank() + k * group.size();
      if (s < BRICK_SAMPLE_COUNT) pool.write(slot, s, staged(k, s));
    }
#if GVDP_IS_GPU_CODE
    __threadfence();
#endif
  }
  group.sync();
  if (group.rank() == 0) publishBrick(cache, key, empty, slot);
}

// Algorithm 2 whole, by a group that keeps its samples in registers: member r evaluates the
// samples r + k * size (k < PER), the group ANDs the empty flags and commits.
template <int PER, class Scope>
GVDP_HD GVDP_INLINE void produceBrick(const Scope& group, const SceneParams& scene,
                                      const CacheView& cache, const BrickPool& pool,
                                      const BrickKey& key) {
  Rgba8 values[PER];
  bool empty = true;
  GVDP_UNROLL
  for (int k = 0; k < PER; ++k) {
    int s = group.rank() + k * group.size();
    values[k] = 0u;
    if (s < BRICK_SAMPLE_COUNT) {
      VoxelSample v = produceBrickSample(scene, key, s);
      values[k] = v.rgba;
      empty = empty && v.empty;
    }
  }
  empty = group.all(empty);
  commitBrick<PER>(group, cache, pool, key, empty, [&](int k, int) { return values[k]; });
}

}  // namespace gvdp
