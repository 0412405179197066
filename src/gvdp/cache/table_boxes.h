// Boxes grown from the indirection table. A brick produced EMPTY or all zero (CLEAR) is listed as
// it is published (cache_ops.h: publishBrick); in the next frame, after its start and beside its
// rays (BrickCache::growTableBoxes), each listed brick grows its box over the bricks the table
// already knows, as an EMPTY brick's box grows by the producer's bound (produce.h: growBoxes). By
// then the rays of the frame that produced it have produced the bricks beyond it too, each tested
// alone, where the producer's bound tests a whole slab from its centre and loosens with it.
// - A plain CLEAR brick's box: the bricks known zero at its level (EMPTY, CLEAR, or not resident
//   under an EMPTY ancestor, as the march skips them: CachedAccess::find). Near a terrain, inside
//   the empty flag's margin, the bricks a grazing ray crosses one by one are mostly zero at their
//   level and no producer bound reaches them (a bound of zero at one level, perlin's and fbm's
//   Taylor bounds with coverage's half-voxel margin, cut perlin's lookups 0.5-3% and fbm's none: a
//   slab beside a brick near the surface is as near it).
// - An EMPTY brick's box, from the producer's: the bricks known empty at every level (EMPTY, or not
//   resident under an EMPTY ancestor), so the box still says what an EMPTY box says and finer
//   levels under it skip it as before.
// A box is a fact of the world (its bricks are zero, or empty), not of the cache: it stays true
// when its bricks are reset.
#pragma once

#include "gvdp/cache/produce.h"

namespace gvdp::detail {

// Largest reach code a table box grows to (8 bricks), and the most bricks a slab it adds may hold:
// a growth tests every entry of its slabs, one warp a box, and an EMPTY box grows from the
// producer's, which may reach far (perlin's walkthrough frame 12, CPU, 300x200: 70 entry loads a
// listed brick on average, 779 at the 99th percentile, 4 492 at most, without the cap; a growth
// took 440 us on an H200).
constexpr int TABLE_BOX_MAX_CODE = 6, TABLE_SLAB_MAX_BRICKS = 128;

// Whether a brick of the window not resident (MISSING, in production or CLEAR) lies under an EMPTY
// ancestor: empty at every level below that one. Every ancestor's entry is loaded before any is
// tested (no chain of loads).
GVDP_HD GVDP_INLINE bool underEmptyAncestor(const CacheView& c, int level, Vec3i g) {
  bool under = false;
#if GVDP_IS_GPU_CODE
#pragma unroll
#endif
  for (int up = 1; up < MAX_LEVELS; ++up) {
    g = halfFloor(g);
    uint32_t a = level + up < c.clipmap.levels ? c.clipmap.windowEntry(level + up, g)
                                               : Clipmap::NOT_IN_WINDOW;
    under |= a != Clipmap::NOT_IN_WINDOW && isEmptyEntry(loadRelaxed32(&c.entries[a]));
  }
  return under;
}

// Whether brick g (global) of `level` is zero at its level (ZERO) or empty at every level (!ZERO)
// by what the table holds (above); unknown (false) outside the window.
template <bool ZERO>
GVDP_HD GVDP_INLINE bool knownAt(const CacheView& c, int level, Vec3i g) {
  uint32_t i = c.clipmap.windowEntry(level, g);
  if (i == Clipmap::NOT_IN_WINDOW) return false;
  uint32_t e = loadRelaxed32(&c.entries[i]);
  if (isEmptyEntry(e) || (ZERO && isClearEntry(e))) return true;
  return !isSlot(e) && underEmptyAncestor(c, level, g);
}

// The table as growBoxes' bound: a slab is clear when every brick of it is known zero (ZERO: a
// CLEAR box) or empty (an EMPTY box, from the producer's box `from`), its bricks shared out among
// the members as the parts of the test.
template <bool ZERO>
struct KnownBound {
  const CacheView& cache;
  EmptyReachCodes from;
  static constexpr bool CLIMBS = false;
  static constexpr int MAX_CODE = TABLE_BOX_MAX_CODE;
  GVDP_HD EmptyReachCodes start() const { return from; }
  GVDP_HD uint32_t entry(const EmptyReachCodes& c) const {
    return ZERO ? clearEntry(c) : emptyEntry(c);
  }
  GVDP_HD int partsFor(int members, int tests) const {
    return members / tests > 1 ? members / tests : 1;
  }
  GVDP_HD bool clear(const BrickKey& k, Vec3i lo, Vec3i hi, int part, int parts) const {
    Vec3i n{hi.x - lo.x + 1, hi.y - lo.y + 1, hi.z - lo.z + 1};
    if (n.x * n.y * n.z > TABLE_SLAB_MAX_BRICKS) return false;
    for (int i = part; i < n.x * n.y * n.z; i += parts) {
      Vec3i d{i % n.x, i / n.x % n.y, i / (n.x * n.y)};
      if (!knownAt<ZERO>(cache, k.level, k.brick + lo + d)) return false;
    }
    return true;
  }
};

// Listed item `item` (of the frame that ended), by a group: the brick's box grown and stored over
// its entry, if it grew; nothing for a brick that is neither EMPTY nor plain CLEAR any more
// (reset), or a CLEAR one grown already (listed twice).
template <class Scope>
GVDP_HD GVDP_INLINE void growTableBox(const Scope& group, const CacheView& cache, uint32_t item) {
  const BrickKey key = cache.listedKeys[item];
  const uint32_t index = cache.clipmap.windowEntry(key.level, key.brick);
  uint32_t e = ENTRY_MISSING;
  if (group.rank() == 0 && index != Clipmap::NOT_IN_WINDOW)
    e = loadRelaxed32(&cache.entries[index]);
  e = group.broadcast(e);
  auto store = [&](const BrickKey&, uint32_t grown) {
    if (group.rank() == 0 && grown != e) storeRelaxed32(&cache.entries[index], grown);
    return false;
  };
  const EmptyReachCodes codes = EmptyReachCodes::unpacked(e & EMPTY_CODES_MASK);  // none: CLEAR
  if (e == ENTRY_CLEAR)
    growBoxes(group, KnownBound<true>{cache, codes}, key, cache.clipmap, store);
  else if (isEmptyEntry(e))
    growBoxes(group, KnownBound<false>{cache, codes}, key, cache.clipmap, store);
}

// The listed items of the last frame: those below its count, within the list.
GVDP_HD GVDP_INLINE uint32_t listedItems(const CacheView& cache) {
  uint32_t n = cache.counters[COUNTER_LISTED_LAST];
  return n < cache.listCapacity ? n : cache.listCapacity;
}

}  // namespace gvdp::detail
