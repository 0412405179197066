// Tiles planned from the frame (issue 16, seed 002): the importance pre-pass
// (sched/importance_map.h) counts the bricks each quadtree node's rays would take, and the
// quadtree subdivision (quadtree.h) cuts the region into the fewest nodes that keep the pool's
// capacity and the payload bound: on the GPU (subtree kernels, PLAN_LEVELS_PER_PASS levels a
// pass) for the cuda backend, the CPU reference for the cpu one; the same tiles either way.
#pragma once

#include <cstdint>
#include <vector>

#include "gvdp/render/frame.h"
#include "gvdp/sched/importance_map.h"
#include "gvdp/sched/scheduler.h"

namespace gvdp::detail {

// The subtree kernels' best levels per pass on an H100 (BENCHMARKS.md, "Tiled frames").
constexpr int PLAN_LEVELS_PER_PASS = 6;
// The capacity a plan fills: 7/8 of the pool, headroom for the bricks the sampled rays miss.
constexpr uint64_t PLAN_CAPACITY_NUM = 7, PLAN_CAPACITY_DEN = 8;

struct PlannedTile {
  int x, y, width, height;  // pixels of the frame planned
  uint64_t bricks;          // the pre-pass's count (the node's)
};

struct TilePlan {
  std::vector<PlannedTile> tiles;  // empty: no plan (the pre-pass gave up: map.failure)
  ImportanceMap map;               // its counts, shape and cost
  double subdivideMs = 0.0;        // the subdivision (GPU: wall clock around its run)
};

// Plans `frame` (a frame or a tile of one) for a pool of `poolBricks`, at most `maxTilePixels`
// rays per tile.
TilePlan planTiles(const Scheduler& scheduler, const FrameSetup& frame, uint64_t poolBricks,
                   int64_t maxTilePixels, const ImportanceOptions& options = {});

}  // namespace gvdp::detail
