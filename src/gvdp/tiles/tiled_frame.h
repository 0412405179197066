// Tiled frames (issue 16, seed 002): a frame whose bricks do not fit the pool, or whose rays do
// not fit the payload, rendered exactly as tiles, each a frame of its own for the scheduler
// (render/frame.h: tileOf; a tile's rays are the image's, bit for bit). A tile that still
// overflows the pool (its frame degraded) is split in four and rendered again, down to
// MIN_TILE_SIDE (with TileOptions::plan, first cut into the tiles the importance pre-pass plans:
// tile_plan.h). A tile that cannot be split (or any frame under --tiles off) that overflows is
// rendered again from an empty cache at coarser LODs until its bricks fit (Lod::bias): degraded,
// but deterministic and without holes. The tiles' images are composed into one; their
// statistics add up.
#pragma once

#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

#include "gvdp/base/image.h"
#include "gvdp/render/frame.h"
#include "gvdp/sched/scheduler.h"

namespace gvdp::detail {

// --tiles: auto (one tile while the frame fits, else tiles), off (never: a frame that overflows
// degrades; one larger than a tile's payload is refused), or an N x N grid (each tile still
// split when it overflows).
struct TileOptions {
  enum class Mode { Auto, Off, Grid };
  Mode mode = Mode::Auto;
  int grid = 1;                       // Grid: tiles per side
  int64_t maxTilePixels = 8ll << 20;  // the payload bound: rays per tile
  // Plan the tiles of a render that overflows from the importance pre-pass (tile_plan.h); false:
  // its quadrants. Off by default: on an H100 the quadrants were faster (BENCHMARKS.md).
  bool plan = false;
};

constexpr int MIN_TILE_SIDE = 8;
constexpr int MAX_IMAGE_SIDE = 32768;
constexpr int64_t MAX_IMAGE_PIXELS = 512ll << 20;  // a 2 GB image on the host
constexpr int MAX_TILE_GRID = 256;

// "auto" | "off" | N (1..MAX_TILE_GRID); throws InputError naming the value.
TileOptions::Mode parseTileMode(std::string_view text, int* grid);

struct PixelTile {
  int x, y, width, height;
  int64_t pixels() const { return static_cast<int64_t>(width) * height; }
};

// The tiles a frame starts from: the whole image (auto, while it holds at most maxTilePixels
// rays; off), an N x N grid, or the image halved until every tile holds at most maxTilePixels.
std::vector<PixelTile> initialTiles(int width, int height, const TileOptions& options);

// The four quadrants of a tile (two halves, or the tile itself, where a side is below
// 2 MIN_TILE_SIDE); empty when it cannot be split.
std::vector<PixelTile> splitTile(const PixelTile& tile);

// What renderTiled did, in FrameStats::tiles / tileSplits (called after each finished tile).
using TileProgress = std::function<void(int tilesDone, int tilesKnown)>;

// The tiles a sequence's last frames kept, so that the next frame starts from them rather than
// from the whole image: a render that overflows is discarded whole (its rays all marched, its
// bricks produced), and the camera's next frame most likely overflows the same way. After a
// frame that started afresh and split, the next `period` frames start from the tiles kept (each
// frame's own, so they follow the camera); then a frame starts afresh again, and the period
// doubles while that one splits too (up to MAX_TILE_REUSE), and ends when it does not. Starting
// tiles change what is rendered, never the image: a tile's rays are the image's, bit for bit.
struct TileMemory {
  std::vector<PixelTile> tiles;  // empty: start afresh
  int width = 0, height = 0;     // the frame they tile
  int left = 0;                  // frames still to start from them
  int period = 0;                // frames between fresh starts (0: none split)
};

constexpr int MAX_TILE_REUSE = 64;

// Renders `frame` (a whole image) with `scheduler`, whose pool holds `poolBricks` (0: none, no
// plans), into `out`: one render when the plan is one tile and it does not overflow (no copy),
// else tile by tile, from the tiles in `memory` when it has some for this frame (then updated).
// The statistics are the tiles' sums (time, counts; the plans' time too), degraded when a kept
// tile is.
FrameStats renderTiled(Scheduler& scheduler, const FrameSetup& frame, Image& out,
                       const TileOptions& options, uint64_t poolBricks,
                       const TileProgress& progress = {}, TileMemory* memory = nullptr);

// Adds a tile's statistics to a frame's.
void addTileStats(FrameStats& total, const FrameStats& tile);

}  // namespace gvdp::detail
