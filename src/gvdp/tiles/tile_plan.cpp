#include "gvdp/tiles/tile_plan.h"

#include <chrono>

#include "gvdp/tiles/quadtree.h"

namespace gvdp::detail {

TilePlan planTiles(const Scheduler& scheduler, const FrameSetup& frame, uint64_t poolBricks,
                   int64_t maxTilePixels, const ImportanceOptions& options) {
  TilePlan plan;
  plan.map = scheduler.importance(frame, options);
  const ImportanceMap& m = plan.map;
  if (m.counts.empty()) return plan;
  auto start = std::chrono::steady_clock::now();
  SumMipmap mipmap;
  mipmap.width = m.blocksX;
  mipmap.height = m.blocksY;
  mipmap.levels = m.levels;
  mipmap.values.assign(m.counts.begin(), m.counts.end());
  SubdivisionParams p;
  p.capacity = poolBricks * PLAN_CAPACITY_NUM / PLAN_CAPACITY_DEN;
  p.maxTilePixels = maxTilePixels;
  p.blockPixels = m.blockPixels;
  p.imageWidth = frame.width;
  p.imageHeight = frame.height;
  std::vector<Tile> tiles;
  if (scheduler.stream()) {
    GpuQuadtree gpu;
    gpu.uploadMipmap(mipmap, scheduler.stream());
    tiles = gpu.subdivide(p, SubdivisionMethod::Subtree, PLAN_LEVELS_PER_PASS, scheduler.stream());
  } else {
    tiles = subdivide(mipmap, p, SubdivisionMethod::Cpu);
  }
  sortCanonical(tiles, m.levels);
  for (const Tile& t : tiles) {
    TileRect r = tileRect(t, m.levels, p);
    plan.tiles.push_back({r.x0, r.y0, r.width, r.height, t.sum});
  }
  plan.subdivideMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return plan;
}

}  // namespace gvdp::detail
