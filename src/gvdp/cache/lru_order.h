// The LRU order of the pool's slots (paper 3.3.4: the free slot list is its head): every slot
// once, by last-used frame (lastUsedFrame of its timestamp), in index order within a frame - a
// stable sort of the slots by last-used frame. Both backends rebuild it at each frame's start and
// mid-frame refill from the order built before, in two passes over the pool and without a sort:
//
// Between a build in frame p and the next, a slot's last-used frame changes only to 0 (its entry
// reset: resetEntry, a cold cache), to p (a ray sampled it, production published it) or above p
// (pt's prefetch for the next frame, p + 1, or a far prefetch's for a later one; a ray's stamp of
// p may follow, cache_ops.h). So a slot still in (0, p) had the same frame at the last build,
// where it stood in order, and the new order is
//   LRU_UNUSED   the slots at 0, by index
//   LRU_KEPT     the last order's slots still in (0, p), in that order
//   LRU_STAMPED  the slots at p, by index
//   LRU_AHEAD    the slots above p, by index (a far prefetch's frames not apart).
// Tests: LruOrder.* (against a sort, over random stamps by these rules, on both backends).
#pragma once

#include <cstdint>

#include "gvdp/cache/cache_ops.h"

namespace gvdp::detail {

enum LruPart : uint32_t { LRU_UNUSED, LRU_KEPT, LRU_STAMPED, LRU_AHEAD, LRU_PARTS };

// The CUDA build's tiles of the pool (cache_kernels.cu): a tile's part sizes fit 16 bits each.
constexpr uint32_t LRU_TILE = 2048;
GVDP_HD GVDP_INLINE uint32_t lruTileCount(uint32_t poolBricks) {
  return (poolBricks + LRU_TILE - 1) / LRU_TILE;
}

// Position i of the pool in a build: slot i's part by index (LRU_PARTS for LRU_KEPT: those come
// from the last order), and the last order's slot at i if it stays in LRU_KEPT (else MAX_SLOTS).
struct LruItem {
  uint32_t part, kept;
};

GVDP_HD GVDP_INLINE LruItem lruItemAt(const uint32_t* timestamps, const uint32_t* order, uint32_t i,
                                      uint32_t builtAt) {
  uint32_t used = lastUsedFrame(timestamps[i]);
  uint32_t part = used == 0         ? LRU_UNUSED
                  : used < builtAt  ? LRU_PARTS
                  : used == builtAt ? LRU_STAMPED
                                    : LRU_AHEAD;
  uint32_t slot = order[i], slotUsed = lastUsedFrame(timestamps[slot]);
  return {part, slotUsed != 0 && slotUsed < builtAt ? slot : MAX_SLOTS};
}

// The free slot list's length (freeListLength) from the parts' sizes, in `frame`: the slots used
// before it may be freed.
GVDP_HD GVDP_INLINE uint32_t lruFreeListLength(uint32_t poolBricks, const uint32_t* size,
                                               uint32_t builtAt, uint32_t frame) {
  uint32_t older = size[LRU_UNUSED] + size[LRU_KEPT];
  if (builtAt < frame) older += size[LRU_STAMPED];
  if (builtAt + 1 < frame) older += size[LRU_AHEAD];
  return freeListLength(poolBricks, size[LRU_UNUSED], older);
}

}  // namespace gvdp::detail
