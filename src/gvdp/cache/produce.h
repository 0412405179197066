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
#include "gvdp/world/producer.h"

namespace gvdp::detail {

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

template <class P>
GVDP_HD GVDP_INLINE VoxelSample produceBrickSample(const P& producer, const BrickKey& key,
                                                   int sample) {
  float vs = ldexpf(producer.voxelSize0(), key.level);
  return producer.voxel(brickSampleCentre(key, sample, producer.voxelSize0()), vs);
}

// The producer's emptiness bound for the box of the samples of the cube of bricks within
// `radius` of a brick, widened by one voxel (the reach of the empty-flag contract,
// world/producer.h). Radius 0: true makes the brick EMPTY unevaluated.
template <class P>
GVDP_HD GVDP_INLINE bool cubeBoundedEmpty(const P& producer, const BrickKey& key, int radius) {
  double vs = ldexp(static_cast<double>(producer.voxelSize0()), key.level);
  Vec3i r{radius, radius, radius};
  Vec3d lo = brickSampleCentre({key.brick - r, key.level}, 0, producer.voxelSize0());
  Vec3d hi =
      brickSampleCentre({key.brick + r, key.level}, BRICK_SAMPLE_COUNT - 1, producer.voxelSize0());
  return producer.emptyBox(lo - Vec3d{vs, vs, vs}, hi + Vec3d{vs, vs, vs}, static_cast<float>(vs));
}

template <class P>
GVDP_HD GVDP_INLINE bool brickBoundedEmpty(const P& producer, const BrickKey& key) {
  return cubeBoundedEmpty(producer, key, 0);
}

// The EMPTY code of an empty brick (brick_key.h: emptyEntry): the largest k whose cube of
// radius 2^k - 1 bricks the producer's bound clears, 0 if none but the brick itself.
template <class P>
GVDP_HD GVDP_INLINE int emptyCubeCode(const P& producer, const BrickKey& key) {
  int code = 0;
  while (code < MAX_EMPTY_CODE && cubeBoundedEmpty(producer, key, (2 << code) - 1)) ++code;
  return code;
}

// A brick found EMPTY may lie in a larger box the producer's bound clears: its ancestors are
// marked EMPTY, each exactly as its own production would have found it (brickBoundedEmpty and
// emptyCubeCode), up to the first the bound does not clear or that is not MISSING (claimed,
// produced or marked already: one CAS each, so a brick in production keeps its state and its
// claimant loses nothing). A ray that meets a missing brick under one skips it unproduced
// (cached_access.h).
template <class P>
GVDP_HD GVDP_INLINE void markBoundedEmptyAncestors(const P& producer, const CacheView& cache,
                                                   BrickKey key) {
  while (key.level + 1 < cache.clipmap.levels) {
    key = {{floorDiv(key.brick.x, 2), floorDiv(key.brick.y, 2), floorDiv(key.brick.z, 2)},
           key.level + 1};
    uint32_t index = cache.clipmap.windowEntry(key.level, key.brick);
    if (index == Clipmap::NOT_IN_WINDOW || !brickBoundedEmpty(producer, key)) return;
    uint32_t* entry = &cache.entries[index];
    uint32_t marked = emptyEntry(emptyCubeCode(producer, key));
    if (atomicCas32(entry, ENTRY_MISSING, marked) != ENTRY_MISSING) return;
  }
}

// Algorithm 2's end, by a group whose member r holds the samples r + k * size (k < PER, with
// PER * size >= BRICK_SAMPLE_COUNT): the leader takes a slot (none for an empty brick), each
// member writes its samples staged(k, sample) to it, the group ORs the occupancy cells of its
// nonzero samples (brick_pool.h) and the leader writes them, each member fences (device scope:
// other blocks read the pool), and the leader publishes the entry once every member's writes
// are fenced.
template <int PER, class Scope, class P, class Staged>
GVDP_HD GVDP_INLINE void commitBrick(const Scope& group, const P& producer, const CacheView& cache,
                                     const BrickPool& pool, const BrickKey& key, bool empty,
                                     Staged staged) {
  uint32_t slot = 0;
  if (group.rank() == 0) slot = empty ? MAX_SLOTS : takeFreeSlot(cache);
  slot = group.broadcast(slot);
  if (!empty && slot != MAX_SLOTS) {
    uint64_t cells = 0;
    GVDP_UNROLL
    for (int k = 0; k < PER; ++k) {
      int s = group.rank() + k * group.size();
      if (s < BRICK_SAMPLE_COUNT) {
        Rgba8 value = staged(k, s);
        pool.write(slot, s, value);
        if (value != 0u) cells |= occupancyCellsOf(brickSampleIndex(s));
      }
    }
    uint32_t low = group.any(static_cast<uint32_t>(cells));
    uint32_t high = group.any(static_cast<uint32_t>(cells >> 32));
    if (group.rank() == 0) pool.occupancy[slot] = uint64_t{high} << 32 | low;
#if GVDP_IS_GPU_CODE
    __threadfence();
#endif
  }
  group.sync();
  if (group.rank() == 0) {
    publishBrick(cache, key, empty ? emptyCubeCode(producer, key) : -1, slot);
    if (empty) markBoundedEmptyAncestors(producer, cache, key);
  }
}

// Algorithm 2 whole, by a group that keeps its samples in registers: member r evaluates the
// samples r + k * size (k < PER) unless the producer's box bound clears the brick, the group ANDs
// the empty flags and commits.
template <int PER, class Scope, class P>
GVDP_HD GVDP_INLINE void produceBrick(const Scope& group, const P& producer, const CacheView& cache,
                                      const BrickPool& pool, const BrickKey& key) {
  Rgba8 values[PER];
  bool bounded = brickBoundedEmpty(producer, key);  // the same answer in every member
  bool empty = true;
  GVDP_UNROLL
  for (int k = 0; k < PER; ++k) {
    int s = group.rank() + k * group.size();
    values[k] = 0u;
    if (s < BRICK_SAMPLE_COUNT && !bounded) {
      VoxelSample v = produceBrickSample(producer, key, s);
      values[k] = v.rgba;
      empty = empty && v.empty;
    }
  }
  empty = group.all(empty);
  commitBrick<PER>(group, producer, cache, pool, key, empty, [&](int k, int) { return values[k]; });
}

}  // namespace gvdp::detail
