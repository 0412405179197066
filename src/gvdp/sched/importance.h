// The importance pre-pass of tiled frames (issue 16; seed 002's importance map): for every node
// of a quadtree over the frame's screen blocks, how many distinct bricks the frame's rays in it
// would take pool slots for. One body for both backends: rays of the frame's own LOD, one per
// stride x stride pixels, march like the direct renderer (the producer sampled, so they end where
// the frame's rays end) and insert each brick they enter, and (node, brick) for each depth of the
// quadtree, into one hash set (bricks the producer's bound clears are EMPTY: no slot); each brick
// found is then classified as production would (any sample not zero: it takes a slot; a brick of
// zeros is EMPTY or CLEAR, cache/brick_key.h);
// each (node, brick) of an occupied brick counts one for its node. The values are thus the exact
// distinct counts of the sampled rays per node (a max-like mipmap: a node's value is at most its
// children's sum, and at least each child's), not sums of block counts, which count every brick
// once per block it spans.
//
// An estimate of the frame's rays, not a bound: with stride 4 a brick (8 voxels, 8 to 16 pixel
// footprints wide at its level) is missed only where its neighbours' rays end before it, a level
// boundary falls between rays, or it shows a sliver at a block edge; a tile that still overflows
// is split as before (tiles/tiled_frame.h), so exactness never depends on it.
#pragma once

#include <cstdint>

#include "gvdp/base/atomics.h"
#include "gvdp/base/quadtree_layout.h"
#include "gvdp/cache/produce.h"
#include "gvdp/render/direct.h"

namespace gvdp::detail {

// Keys: depth 4 bits | node 22 bits (y << depth | x) | level 4 | three 11-bit brick coordinates
// relative to the eye's brick: 63 bits, so no key is the free marker. Depth BRICK_DEPTH marks a
// brick's own key (node 0), which carries its production verdict.
constexpr int IMPORTANCE_MAX_LEVELS = 11;
constexpr int IMPORTANCE_COORD_BITS = 11;
constexpr int IMPORTANCE_COORD_REACH = 1 << (IMPORTANCE_COORD_BITS - 1);
constexpr uint64_t IMPORTANCE_FREE = ~uint64_t{0};
constexpr uint64_t IMPORTANCE_BRICK_DEPTH = 15;
constexpr int IMPORTANCE_DEPTH_SHIFT = 59, IMPORTANCE_NODE_SHIFT = 37;
constexpr uint64_t IMPORTANCE_BRICK_BITS = (uint64_t{1} << IMPORTANCE_NODE_SHIFT) - 1;
static_assert(MAX_LEVELS <= 16, "levels take 4 bits of an importance key");

// Status words (ImportanceSetup::status).
constexpr int IMPORTANCE_ENTRIES = 0;  // keys inserted
constexpr int IMPORTANCE_FULL = 1;     // nonzero: the table filled up; the counts are invalid
constexpr int IMPORTANCE_RANGE = 2;    // nonzero: a brick beyond the keys' reach (no counts)
constexpr int IMPORTANCE_BRICKS = 3;   // bricks listed (ImportanceSetup::bricks)
constexpr int IMPORTANCE_STATUS_WORDS = 4;

struct ImportanceSetup {
  int blockPixels;    // a block is blockPixels x blockPixels pixels (a multiple of stride)
  int stride;         // one ray per stride x stride pixels, at the cell's centre
  int levels;         // K: the quadtree covers 2^K x 2^K blocks
  int raysX, raysY;   // ceil(width / stride) x ceil(height / stride)
  uint64_t* table;    // open addressing, IMPORTANCE_FREE where free; size tableMask + 1
  uint8_t* occupied;  // per table slot: a brick key whose brick production would give a slot
  uint64_t* bricks;   // the slots of the bricks' own keys, in insertion order (tableMask + 1)
  uint64_t tableMask;
  uint32_t maxEntries;  // past it the table counts as full (3/4 of its size)
  uint32_t* counts;     // per node, root first (base/quadtree_layout.h)
  uint32_t* status;     // IMPORTANCE_STATUS_WORDS words

  GVDP_HD uint32_t rays() const { return static_cast<uint32_t>(raysX) * raysY; }
  GVDP_HD uint64_t tableSize() const { return tableMask + 1; }
};

GVDP_HD GVDP_INLINE uint64_t mixKey(uint64_t k) {  // splitmix64's finaliser
  k = (k ^ (k >> 30)) * 0xbf58476d1ce4e5b9ull;
  k = (k ^ (k >> 27)) * 0x94d049bb133111ebull;
  return k ^ (k >> 31);
}

// Inserts `key`; true when this call inserted it (a first sighting). A table past maxEntries,
// or a probe sequence past IMPORTANCE_MAX_PROBES, raises IMPORTANCE_FULL, after which nothing is
// inserted (the pass is run again with a larger table): a full table is never probed through.
constexpr uint64_t IMPORTANCE_MAX_PROBES = 4096;
GVDP_HD GVDP_INLINE bool insertImportanceKey(const ImportanceSetup& s, uint64_t key,
                                             uint64_t* slot = nullptr) {
  if (loadAcquire32(s.status + IMPORTANCE_FULL)) return false;
  uint64_t h = mixKey(key);
  for (uint64_t probe = 0; probe < IMPORTANCE_MAX_PROBES && probe <= s.tableMask; ++probe) {
    uint64_t at = (h + probe) & s.tableMask;
    uint64_t found = atomicCas64(s.table + at, IMPORTANCE_FREE, key);
    if (found == key) return false;
    if (found == IMPORTANCE_FREE) {
      if (atomicAdd32(s.status + IMPORTANCE_ENTRIES, 1) >= s.maxEntries)
        atomicExch32(s.status + IMPORTANCE_FULL, 1);
      if (slot) *slot = at;
      return true;
    }
  }
  atomicExch32(s.status + IMPORTANCE_FULL, 1);
  return false;
}

// The slot of `key` (inserted by an earlier pass), or the table's size when it is not there.
GVDP_HD GVDP_INLINE uint64_t findImportanceKey(const ImportanceSetup& s, uint64_t key) {
  uint64_t h = mixKey(key);
  for (uint64_t probe = 0; probe < IMPORTANCE_MAX_PROBES && probe <= s.tableMask; ++probe) {
    uint64_t at = (h + probe) & s.tableMask, found = s.table[at];
    if (found == key) return at;
    if (found == IMPORTANCE_FREE) break;
  }
  return s.tableSize();
}

// Global brick coordinates of the local origin, and local ones of the eye's brick, at a level.
GVDP_HD GVDP_INLINE Vec3i importanceOriginBrick(const FrameSetup& f, int level) {
  double side = static_cast<double>(f.lod.voxelSize(level)) * BRICK_WIDTH;
  auto brick = [&](double o) { return static_cast<int>(floor(o / side + 0.5)); };
  return {brick(f.localOrigin.x), brick(f.localOrigin.y), brick(f.localOrigin.z)};
}
GVDP_HD GVDP_INLINE Vec3i importanceEyeBrick(const FrameSetup& f, int level) {
  return floorToInt(f.eye * (1.0f / (f.lod.voxelSize(level) * BRICK_WIDTH)));
}

// Pass 1, the march: the direct renderer's access (samples from the producer) inserting, for
// each brick entered that the producer's bound does not clear, the brick's own key and
// (node, brick) for the ray's node at every depth.
template <class P>
struct CountingAccess {
  DirectAccess<P> direct;
  const ImportanceSetup& setup;
  int blockX, blockY;  // the ray's block

  GVDP_HD BrickLookup lookup(int level, Vec3i brick) const {
    const FrameSetup& f = direct.frame;
    if (brickBoundedEmpty(direct.producer,
                          BrickKey{brick + importanceOriginBrick(f, level), level}))
      return {BrickState::Empty, 0u, level, brick, 0, 0u};  // this brick alone
    Vec3i rel = brick - importanceEyeBrick(f, level);
    auto inReach = [](int c) { return c > -IMPORTANCE_COORD_REACH && c < IMPORTANCE_COORD_REACH; };
    if (!inReach(rel.x) || !inReach(rel.y) || !inReach(rel.z)) {
      atomicExch32(setup.status + IMPORTANCE_RANGE, 1);
      return {BrickState::Resident, 0u, level, brick};
    }
    constexpr int B = IMPORTANCE_COORD_BITS;
    auto coord = [](int c) { return static_cast<uint64_t>(c + IMPORTANCE_COORD_REACH); };
    uint64_t brickBits = static_cast<uint64_t>(level) << (3 * B) | coord(rel.x) << (2 * B) |
                         coord(rel.y) << B | coord(rel.z);
    uint64_t slot = 0;
    // (node, brick) for the ray's node at `depth`; true when this call inserted it.
    auto insertNode = [&](int depth) {
      int shift = setup.levels - depth;
      uint64_t node =
          static_cast<uint64_t>(blockY >> shift) << depth | static_cast<uint64_t>(blockX >> shift);
      return insertImportanceKey(setup, static_cast<uint64_t>(depth) << IMPORTANCE_DEPTH_SHIFT |
                                            node << IMPORTANCE_NODE_SHIFT | brickBits);
    };
    if (insertImportanceKey(setup, IMPORTANCE_BRICK_DEPTH << IMPORTANCE_DEPTH_SHIFT | brickBits,
                            &slot)) {
      setup.bricks[atomicAdd32(setup.status + IMPORTANCE_BRICKS, 1)] = slot;
      for (int depth = 0; depth <= setup.levels; ++depth) insertNode(depth);
    } else {
      // Another ray has it: its nodes for this ray's block may still be new. Finest first: a
      // node that has it means every coarser node has it too.
      for (int depth = setup.levels; depth >= 0 && insertNode(depth); --depth) {
      }
    }
    return {BrickState::Resident, 0u, level, brick};
  }
  GVDP_HD Vec4f sample(const BrickLookup& b, Vec3f p) const { return direct.sample(b, p); }
};

// Pass 1 for pre-pass ray `ray` (row-major over raysX x raysY).
template <class P>
GVDP_HD GVDP_INLINE void countRayBricks(const FrameSetup& frame, const P& producer,
                                        const ImportanceSetup& s, uint32_t ray) {
  int rx = static_cast<int>(ray % static_cast<uint32_t>(s.raysX));
  int ry = static_cast<int>(ray / static_cast<uint32_t>(s.raysX));
  int px = rx * s.stride + s.stride / 2, py = ry * s.stride + s.stride / 2;
  px = px < frame.width ? px : frame.width - 1;
  py = py < frame.height ? py : frame.height - 1;
  CountingAccess<P> access{{frame, producer}, s, px / s.blockPixels, py / s.blockPixels};
  Ray r = frame.primaryRay(px, py);
  RayState state = initialRayState();
  march(r, frame.lod, state, access);
}

// Pass 2, per listed brick: production's verdict (a sample not zero: the brick takes a slot),
// read from the producer as production reads it; the samples first, first + step, ...
// (a thread per brick on the CPU, a warp on the GPU).
GVDP_HD GVDP_INLINE BrickKey importanceBrick(const FrameSetup& frame, uint64_t key) {
  constexpr int B = IMPORTANCE_COORD_BITS;
  constexpr uint64_t MASK = (uint64_t{1} << B) - 1;
  int level = static_cast<int>((key >> (3 * B)) & 15);
  auto coord = [&](int shift) {
    return static_cast<int>((key >> shift) & MASK) - IMPORTANCE_COORD_REACH;
  };
  return {Vec3i{coord(2 * B), coord(B), coord(0)} + importanceEyeBrick(frame, level) +
              importanceOriginBrick(frame, level),
          level};
}

template <class P>
GVDP_HD GVDP_INLINE bool importanceSampleOccupied(const P& producer, const BrickKey& brick,
                                                  int sample) {
  return produceBrickSample(producer, brick, sample).rgba != 0u;
}

// Pass 3, per table slot: a node's key counts one for the node when its brick is occupied.
GVDP_HD GVDP_INLINE void countImportanceNode(const ImportanceSetup& s, uint64_t slot) {
  uint64_t key = s.table[slot];
  uint64_t depth = key >> IMPORTANCE_DEPTH_SHIFT;
  if (key == IMPORTANCE_FREE || depth == IMPORTANCE_BRICK_DEPTH) return;
  uint64_t brick = findImportanceKey(
      s, IMPORTANCE_BRICK_DEPTH << IMPORTANCE_DEPTH_SHIFT | (key & IMPORTANCE_BRICK_BITS));
  if (brick == s.tableSize() || !s.occupied[brick]) return;
  uint64_t node = (key >> IMPORTANCE_NODE_SHIFT) & ((uint64_t{1} << 22) - 1);
  int d = static_cast<int>(depth);
  int x = static_cast<int>(node & ((uint64_t{1} << d) - 1)), y = static_cast<int>(node >> d);
  atomicAdd32(s.counts + mipmapIndex(d, x, y), 1);
}

}  // namespace gvdp::detail
