// The order in which a frame's first rays take the screen: the previous frame's most costly parts
// first (longest processing time first). Warps take work as they free up, so a frame ends when
// the last work taken is done; taken in row-major order, that was as likely costly as cheap, and
// SMs fell idle one by one for 0.5 ms while a few finished costly tiles (a floor frame of
// random-spheres, `gvdp timeline --again`, H100). A frame measures what each block of 4x4 tiles
// cost: the SM cycles of the longest of the warps that render its rays afresh (counting the rays
// run again after a production too, pt's spinning walks lost 2-4% of their FPS, H100). A block's
// warps run side by side, so the longest is the block's critical path, and the frame cannot end
// sooner than the longest warp's start plus its cycles: in pt's render-only frames (perlin's and
// random-spheres' walkthrough frame 12 again, H200) the last warps to finish were those of the
// first blocks, 1.4-1.7 ms long against a median of 67-95 us. The next frame of the same size
// moves those costs with the camera's turn, takes each block's largest cost among its neighbours
// (the camera's step moves near things by a block) and sorts the blocks by it
// (tile_order_cuda.h). Any order gives the same image: rays are independent.
//
// Measured on the H100 (walkthrough and forward, sp and pt, floors), with the sum of the warps'
// cycles as a block's cost: sorting 8x8 tiles forest's floors x1.15 (their costs move more between
// frames, and neighbours no longer run together); blocks by their own cost x0.973 over 20 cells
// but forest's walkthrough x1.09; with the neighbourhood's largest cost x0.94 over 50 cells,
// forest's walkthrough x0.92-0.99 (BENCHMARKS.md, session 21). The longest warp instead of the
// sum, on an H200 (25 pt cells, two calls of 2 rounds): floors x0.990-0.991, FPS x1.002-1.004;
// random-spheres' walkthrough frame 12 again 2.84-2.91 -> 2.73-2.78 ms; sp's 25 cells within the
// noise (floors x0.996, x1.005; session 47).
#pragma once

#include <cmath>
#include <cstdint>

#include "gvdp/sched/ray_tasks.h"

namespace gvdp::detail {

struct TileOrder {
  const uint32_t* order = nullptr;  // per rank, the block taken (null: row-major)
  uint32_t* cost = nullptr;         // per block, its longest warp's cycles (null: none)
};

// What is ordered is blocks of 4x4 tiles (32x32 pixels), each tile's pixels in tiledPixel's
// order, the tiles of a block row-major (2x2 tiles: no better; H100).
constexpr int ORDER_BLOCK = 4;  // tiles a side
constexpr int TILE_ITEMS = TILE * TILE, ORDER_BLOCK_ITEMS = ORDER_BLOCK * ORDER_BLOCK * TILE_ITEMS;

GVDP_HD GVDP_INLINE int orderBlocksX(const FrameSetup& f) {
  return (f.width + TILE * ORDER_BLOCK - 1) / (TILE * ORDER_BLOCK);
}
GVDP_HD GVDP_INLINE int orderBlockCount(const FrameSetup& f) {
  return orderBlocksX(f) * ((f.height + TILE * ORDER_BLOCK - 1) / (TILE * ORDER_BLOCK));
}
// Items of an ordered first pass (some past the image's edges).
GVDP_HD GVDP_INLINE int orderedItemCount(const FrameSetup& f) {
  return orderBlockCount(f) * ORDER_BLOCK_ITEMS;
}

// The block of item i.
GVDP_HD GVDP_INLINE int orderedBlock(const TileOrder& t, int i) {
  int rank = i / ORDER_BLOCK_ITEMS;
  return t.order ? static_cast<int>(t.order[rank]) : rank;
}

// The pixel of item i, the blocks taken in `t`'s order; -1 outside the image.
GVDP_HD GVDP_INLINE int orderedPixel(const FrameSetup& f, const TileOrder& t, int i) {
  if (i < 0 || i >= orderedItemCount(f)) return -1;
  int block = orderedBlock(t, i), inBlock = i % ORDER_BLOCK_ITEMS;
  int tile = inBlock / TILE_ITEMS, inTile = inBlock % TILE_ITEMS;
  int x = ((block % orderBlocksX(f)) * ORDER_BLOCK + tile % ORDER_BLOCK) * TILE + inTile % TILE;
  int y = ((block / orderBlocksX(f)) * ORDER_BLOCK + tile / ORDER_BLOCK) * TILE + inTile / TILE;
  return x < f.width && y < f.height ? y * f.width + x : -1;
}

// The block of a pixel.
GVDP_HD GVDP_INLINE int blockOfPixel(const FrameSetup& f, int pixel) {
  constexpr int SIDE = TILE * ORDER_BLOCK;
  return (pixel / f.width / SIDE) * orderBlocksX(f) + pixel % f.width / SIDE;
}

// The block of `before` (a frame of `now`'s size) that saw the direction `now`'s block sees at its
// centre, the nearest one for a direction outside its view: the costs of the last frame moved
// with the camera's turn (a walkthrough's yaw moves the screen by up to half a block a frame).
GVDP_HD GVDP_INLINE int reprojectedBlock(const FrameSetup& now, const FrameSetup& before,
                                         int block) {
  constexpr int SIDE = TILE * ORDER_BLOCK;
  int bx = block % orderBlocksX(now), by = block / orderBlocksX(now);
  int cx = bx * SIDE + SIDE / 2, cy = by * SIDE + SIDE / 2;
  Vec3f d =
      now.primaryRay(cx < now.width ? cx : now.width - 1, cy < now.height ? cy : now.height - 1).d;
  float z = dot(d, before.basis.forward);
  if (z <= 1e-3f) return block;
  float w = static_cast<float>(before.imageWidth), h = static_cast<float>(before.imageHeight);
  float sx = dot(d, before.basis.right) / z / before.tanHalfFov;
  float sy = dot(d, before.basis.up) / z / (before.tanHalfFov * h / w);
  float ix = (sx + 1.0f) * 0.5f * w - 0.5f - static_cast<float>(before.tileX);
  float iy = (1.0f - sy) * 0.5f * h - 0.5f - static_cast<float>(before.tileY);
  auto clampTo = [](float v, int n) {
    return v < 0.0f ? 0 : v > n - 1.0f ? n - 1 : static_cast<int>(v);
  };
  return blockOfPixel(before,
                      clampTo(iy, before.height) * before.width + clampTo(ix, before.width));
}

// The largest cost of a block and its 8 neighbours: a block the last frame found cheap is taken
// late only if everything around it was cheap too.
GVDP_HD GVDP_INLINE uint32_t neighbourhoodCost(const uint32_t* cost, const FrameSetup& f,
                                               int block) {
  const int bx = block % orderBlocksX(f), by = block / orderBlocksX(f);
  const int nx = orderBlocksX(f), ny = orderBlockCount(f) / nx;
  uint32_t c = 0;
  for (int y = by - 1; y <= by + 1; ++y)
    for (int x = bx - 1; x <= bx + 1; ++x)
      if (x >= 0 && x < nx && y >= 0 && y < ny) c = c > cost[y * nx + x] ? c : cost[y * nx + x];
  return c;
}

// The sort key of a block's cost: 8 steps an octave, in 8 bits (costs 1.09x apart sort apart).
GVDP_HD GVDP_INLINE uint32_t blockCostKey(uint32_t cycles) {
  if (cycles == 0) return 0;
  int k = static_cast<int>(8.0f * log2f(static_cast<float>(cycles)));
  return static_cast<uint32_t>(k < 0 ? 0 : k > 255 ? 255 : k);
}

#if defined(__CUDACC__)
// A warp's cycles on item i's rays: its block's cost if the longest (one lane of a warp calls it).
__device__ inline void noteBlockCost(const TileOrder& t, int i, uint32_t cycles) {
  if (t.cost) atomicMax(&t.cost[orderedBlock(t, i)], cycles);
}

__device__ inline uint32_t smCycles() {
  return static_cast<uint32_t>(clock());
}
#endif

}  // namespace gvdp::detail
