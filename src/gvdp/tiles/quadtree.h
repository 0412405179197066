// Tiles of a render target too large for memory, by quadtree subdivision of an importance map
// (seed paper, "GPU quadtree subdivision for out-of-core rendering"). The importance is a grid
// of screen blocks, each an upper bound of the bricks the block needs; its sum-mipmap bounds
// what any square node of blocks needs. Top-down, a node within the capacity (and the pixel
// limit) is a tile, a node past it splits into four, a node outside the image is dropped.
// Invariant: every method's tiles cover each valid block exactly once, and are the same set
// (compare after sortCanonical); one node rule (decideNode) serves the CPU reference and every
// GPU method: MultiPass (a pass per level), Subtree (the seed's L levels per pass) and Dynamic
// (CUDA Dynamic Parallelism, a launch per subdivided node).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "gvdp/base/defs.h"
#include "gvdp/base/gpu.h"
#include "gvdp/base/quadtree_layout.h"

namespace gvdp::detail {

// The padded grid is at most 2^13 blocks a side (a 2^13 x 2^13 sum-mipmap is ~0.7 GB).
constexpr int QUADTREE_MAX_LEVELS = 13;
constexpr int QUADTREE_MAX_LEVELS_PER_PASS = 8;

struct SubdivisionParams {
  uint64_t capacity = 0;                // bricks a tile may need (its sum)
  int64_t maxTilePixels = 0;            // pixels a tile may cover, clipped to the image
  int blockPixels = 1;                  // an importance block is blockPixels x blockPixels pixels
  int imageWidth = 0, imageHeight = 0;  // pixels; ceil(image / blockPixels) = the blocks
};

struct TileRect {
  int x0, y0, width, height;  // pixels, clipped to the image
  friend bool operator==(const TileRect&, const TileRect&) = default;
};

// Node (depth, x, y): depth 0 is the root (the padded 2^K grid), depth K a single block.
struct Tile {
  int depth, x, y;
  uint64_t sum;    // bricks its blocks need at most
  bool overflows;  // a single block past the capacity or the pixel limit, emitted anyway
  friend bool operator==(const Tile&, const Tile&) = default;
};

enum class NodeAction : uint8_t { Drop, Emit, Subdivide };

struct NodeDecision {
  NodeAction action;
  bool overflows;
  uint64_t sum;
};

// What the rule reads: the sums, the grid and the limits. POD, passed to kernels by value.
struct QuadtreeView {
  const uint64_t* sums;  // root first (mipmapDepthOffset)
  int levels;            // K
  int blocksX, blocksY;  // valid blocks; the rest of the 2^K square is zero padding
  SubdivisionParams params;

  GVDP_HD uint64_t sum(int depth, int x, int y) const { return sums[mipmapIndex(depth, x, y)]; }
};

// A node's pixels, clipped to the image; width or height 0 when it lies outside.
GVDP_HD inline TileRect nodePixelRect(int levels, const SubdivisionParams& p, int depth, int x,
                                      int y) {
  int64_t side = (int64_t{1} << (levels - depth)) * p.blockPixels;
  int64_t x0 = x * side, y0 = y * side;
  int64_t x1 = x0 + side < p.imageWidth ? x0 + side : p.imageWidth;
  int64_t y1 = y0 + side < p.imageHeight ? y0 + side : p.imageHeight;
  return {static_cast<int>(x0), static_cast<int>(y0), static_cast<int>(x1 > x0 ? x1 - x0 : 0),
          static_cast<int>(y1 > y0 ? y1 - y0 : 0)};
}

// A node's first (top-left) block is valid exactly when any of its blocks is.
GVDP_HD inline bool nodeIsValid(const QuadtreeView& q, int depth, int x, int y) {
  int shift = q.levels - depth;
  return (int64_t{x} << shift) < q.blocksX && (int64_t{y} << shift) < q.blocksY;
}

// The rule, the one place every method asks: drop a node without a valid block; emit a single
// block always (flagged when it breaks a limit) and a larger node when it keeps both limits (the
// sum bounds its bricks: a sum, not a max, because the blocks' bricks add up); else subdivide.
GVDP_HD inline NodeDecision decideNode(const QuadtreeView& q, int depth, int x, int y) {
  if (!nodeIsValid(q, depth, x, y)) return {NodeAction::Drop, false, 0};
  uint64_t sum = q.sum(depth, x, y);
  TileRect r = nodePixelRect(q.levels, q.params, depth, x, y);
  bool fits = sum <= q.params.capacity && int64_t{r.width} * r.height <= q.params.maxTilePixels;
  if (fits) return {NodeAction::Emit, false, sum};
  if (depth == q.levels) return {NodeAction::Emit, true, sum};
  return {NodeAction::Subdivide, false, sum};
}

// The sum-mipmap on the host: `values` root first (mipmapDepthOffset), 64-bit sums (no
// saturation: 2^26 blocks of 2^32 - 1 bricks fit).
struct SumMipmap {
  int width = 0, height = 0;  // valid blocks
  int levels = 0;             // K: the padded grid is 2^K x 2^K
  std::vector<uint64_t> values;

  QuadtreeView view(const SubdivisionParams& p) const {
    return {values.data(), levels, width, height, p};
  }
};

// K for a width x height grid of blocks: the least with 2^K >= both; throws InputError past
// QUADTREE_MAX_LEVELS or for an empty grid.
int quadtreeLevels(int width, int height);
// `importance`: width x height values, row-major.
SumMipmap buildSumMipmap(const uint32_t* importance, int width, int height);

// Throws InputError when the params do not fit the grid (ceil(image / blockPixels) must be the
// blocks) or are out of range.
void checkSubdivisionParams(const SumMipmap& m, const SubdivisionParams& p);
void checkSubdivisionParams(int width, int height, const SubdivisionParams& p);

enum class SubdivisionMethod { Cpu, MultiPass, Subtree, Dynamic };
const char* methodName(SubdivisionMethod m);

// A GPU method with its levels per pass (1 where it has none).
struct GpuSubdivision {
  SubdivisionMethod method;
  int levelsPerPass;
};
// Every GPU method this build has: one pass per level, subtree kernels of 1..8 levels, and
// dynamic parallelism when it is built (GVDP_CDP).
std::vector<GpuSubdivision> gpuSubdivisions();

// Passes of one subdivision: the host's launches and the active nodes each began with (nodes
// still to decide, all at that pass's depth); Dynamic has one host launch and counts its
// device-side launches instead.
struct SubdivisionStats {
  int passes = 0;
  std::vector<uint64_t> activeNodes;  // per pass
  uint64_t deviceLaunches = 0;        // Dynamic only
};

// Tiles on the host: the recursive reference for Cpu; the GPU methods through a GpuQuadtree made
// for the call (upload and allocation included: time a GpuQuadtree's run() instead).
std::vector<Tile> subdivide(const SumMipmap& m, const SubdivisionParams& p,
                            SubdivisionMethod method = SubdivisionMethod::Cpu,
                            int levelsPerPass = 6);
// The passes a GPU method makes (and Dynamic's device launches), computed on the CPU; Cpu has
// none. levelsPerPass: Subtree only.
SubdivisionStats plannedPasses(const SumMipmap& m, const SubdivisionParams& p,
                               SubdivisionMethod method, int levelsPerPass = 6);

// The canonical order, by the pixel rectangle's (y0, x0): tiles are disjoint, so this is total.
void sortCanonical(std::vector<Tile>& tiles, int levels);
TileRect tileRect(const Tile& t, int levels, const SubdivisionParams& p);

// The subdivision on the GPU, with device buffers kept between calls so that run() times the
// subdivision alone. In builds without CUDA every member but the constructor and destructor
// throws InputError.
class GpuQuadtree {
 public:
  GpuQuadtree();
  ~GpuQuadtree();
  GpuQuadtree(const GpuQuadtree&) = delete;
  GpuQuadtree& operator=(const GpuQuadtree&) = delete;

  // The importance grid to the device (width x height, row-major); then buildMipmap().
  void upload(const uint32_t* importance, int width, int height, GpuStream stream);
  void buildMipmap(GpuStream stream);
  // A mipmap built elsewhere, instead of upload() + buildMipmap().
  void uploadMipmap(const SumMipmap& m, GpuStream stream);
  SumMipmap downloadMipmap(GpuStream stream) const;

  // Subdivides; returns the tile count, the tiles stay on the device (tiles()). Blocks until
  // done (every method reads counts back). levelsPerPass: Subtree only, 1..8.
  uint64_t run(const SubdivisionParams& p, SubdivisionMethod method, int levelsPerPass,
               GpuStream stream, SubdivisionStats* stats = nullptr);
  // The last run's tiles, in the order the device wrote them.
  std::vector<Tile> tiles(GpuStream stream) const;
  std::vector<Tile> subdivide(const SubdivisionParams& p, SubdivisionMethod method,
                              int levelsPerPass, GpuStream stream) {
    run(p, method, levelsPerPass, stream);
    return tiles(stream);
  }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gvdp::detail
