// Lookahead production: a ray that stops on a brick that is not resident goes on along its path
// on a copy of its state and claims the missing bricks it meets, so that the chain of bricks it
// would otherwise wait for one after the other (stop, produce, march on, stop again) is produced
// in parallel. Nothing is composited into the ray's own state: the image never depends on it.
//
// The copy marches as the ray would (render/march.h), with each brick that is not resident
// standing in by its nearest resident coarser ancestor (CachedAccess::standIn) - which predicts
// where the ray becomes opaque, and the lookahead ends there - or passed through when none is
// within the levels the caller allows (none in pt's frame tail, pt_body.h: lookaheadPlan; one
// for pt's prefetch: PT_PREFETCH_STAND_IN_LEVELS). It also ends after the `cap` bricks that
// follow the one the ray stopped on (resident, empty or not there yet: a bound on its cost, which
// is a march - without one, a lookahead through resident bricks marched the rest of the ray a
// second time: pt 1.5x slower on perlin, H100), when the copy leaves the last level, or when
// OnMiss::goesOn() says so (pt's prefetch past the frame's rays). A brick it meets MISSING goes
// to OnMiss (which may decline: no task id left, pt_tasks.h: StartAhead). It stamps no timestamp: a
// brick only the lookahead read was not sampled (over-production, cache_view.h).
#pragma once

#include "gvdp/cache/cached_access.h"

namespace gvdp::detail {

template <class Pool, class OnMiss, PoolReads READS>
struct LookaheadAccess {
  CachedAccess<Pool, OnMiss, READS, false> cached;
  uint32_t left;  // bricks it may still enter
  // How many levels coarser a stand-in may be (0: none, a brick not resident is passed through,
  // as when none stands in; STAND_INS_ANY: any).
  int standInLevels = STAND_INS_ANY;
  int lastLevel = -1;
  Vec3i last{0, 0, 0};  // the last one entered (a coarser stand-in is looked up at every sample)

  GVDP_HD BrickLookup lookup(int level, Vec3i brick) {
    if (level != lastLevel || !(brick == last)) {
      if (left == 0 || !cached.onMiss.goesOn()) return {BrickState::Stop, 0u, level, brick};
      --left;
      lastLevel = level;
      last = brick;
    }
    BrickLookup b = cached.find(level, brick);
    if (b.state != BrickState::Stop) return b;
    return cached.standIn(level, brick, standInLevels);
  }

  GVDP_HD Vec4f sample(const BrickLookup& b, Vec3f p) { return cached.sample(b, p); }
};

// Looks ahead of a ray stopped in state s (the state itself is not changed); returns the bricks
// it entered.
template <PoolReads READS, class Pool, class OnMiss>
GVDP_HD uint32_t lookAhead(const Ray& ray, const Lod& lod, RayState s, const CacheView& cache,
                           const Pool& pool, OnMiss onMiss, uint32_t cap,
                           int standInLevels = STAND_INS_ANY) {
  if (cap == 0) return 0;
  LookaheadAccess<Pool, OnMiss, READS> access{{cache, pool, lod, onMiss}, cap + 1, standInLevels};
  march(ray, lod, s, access);
  return cap + 1 - access.left;
}

}  // namespace gvdp::detail
