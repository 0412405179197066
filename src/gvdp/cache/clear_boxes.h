// CLEAR boxes (brick_key.h: ENTRY_CLEAR), grown between frames from the indirection table. A brick
// produced all zero is published CLEAR alone and its key listed (cache_ops.h: publishBrick); at the
// next frame's start each listed brick still plain CLEAR grows a box over the bricks the table
// already knows zero at its level (EMPTY, CLEAR, or not resident under an EMPTY ancestor, as the
// march skips them: CachedAccess::find), as an EMPTY brick's box grows by the producer's bound
// (produce.h: growBoxes). By then the rays of the frame that produced it have produced the bricks
// beyond it too. Near a terrain, inside the empty flag's margin, the bricks a grazing ray crosses
// one by one are mostly zero at their level and no producer bound reaches them (a bound of zero
// at one level, perlin's and fbm's Taylor bounds with coverage's half-voxel margin, cut perlin's
// lookups 0.5-3% and fbm's none: a slab beside a brick near the surface is as near it).
#pragma once

#include "gvdp/cache/produce.h"

namespace gvdp::detail {

// Largest reach code of a CLEAR box (8 bricks): a growth tests every entry of its slabs.
constexpr int CLEAR_BOX_MAX_CODE = 6;

// Whether brick g (global) of `level` is zero at its level by what the table holds (above);
// unknown (false) outside the window.
GVDP_HD GVDP_INLINE bool knownZeroAt(const CacheView& c, int level, Vec3i g) {
  uint32_t i = c.clipmap.windowEntry(level, g);
  if (i == Clipmap::NOT_IN_WINDOW) return false;
  uint32_t e = loadRelaxed32(&c.entries[i]);
  if (isEmptyEntry(e) || isClearEntry(e)) return true;
  if (isSlot(e)) return false;
  for (int up = level + 1; up < c.clipmap.levels; ++up) {
    g = halfFloor(g);
    uint32_t a = c.clipmap.windowEntry(up, g);
    if (a != Clipmap::NOT_IN_WINDOW && isEmptyEntry(loadRelaxed32(&c.entries[a]))) return true;
  }
  return false;
}

// The table as growBoxes' bound: a slab is clear when every brick of it is known zero, its
// bricks shared out among the members as the parts of the test.
struct KnownZeroBound {
  const CacheView& cache;
  static constexpr bool ZERO_AT_LEVEL = true;
  static constexpr int MAX_CODE = CLEAR_BOX_MAX_CODE;
  GVDP_HD int partsFor(int members, int tests) const {
    return members / tests > 1 ? members / tests : 1;
  }
  GVDP_HD bool clear(const BrickKey& k, Vec3i lo, Vec3i hi, int part, int parts) const {
    Vec3i n{hi.x - lo.x + 1, hi.y - lo.y + 1, hi.z - lo.z + 1};
    for (int i = part; i < n.x * n.y * n.z; i += parts) {
      Vec3i d{i % n.x, i / n.x % n.y, i / (n.x * n.y)};
      if (!knownZeroAt(cache, k.level, k.brick + lo + d)) return false;
    }
    return true;
  }
};

// Listed item `item` (of the frame that ended), by a group: the brick's box grown and stored over
// its plain CLEAR entry; nothing for a brick that is no longer plain CLEAR (reset, or listed
// twice).
template <class Scope>
GVDP_HD GVDP_INLINE void growClearBox(const Scope& group, const CacheView& cache, uint32_t item) {
  const BrickKey key = cache.clearKeys[item];
  const uint32_t index = cache.clipmap.windowEntry(key.level, key.brick);
  uint32_t plain = 0u;
  if (group.rank() == 0)
    plain = index != Clipmap::NOT_IN_WINDOW && loadRelaxed32(&cache.entries[index]) == ENTRY_CLEAR;
  if (!group.broadcast(plain)) return;
  growBoxes(group, KnownZeroBound{cache}, key, cache.clipmap, [&](const BrickKey&, uint32_t entry) {
    if (group.rank() == 0 && entry != ENTRY_CLEAR) storeRelaxed32(&cache.entries[index], entry);
    return false;
  });
}

// The listed items of the frame that ended: those below the count, within the list.
GVDP_HD GVDP_INLINE uint32_t clearItems(const CacheView& cache) {
  uint32_t n = cache.counters[COUNTER_CLEAR];
  return n < cache.clearCapacity ? n : cache.clearCapacity;
}

}  // namespace gvdp::detail
