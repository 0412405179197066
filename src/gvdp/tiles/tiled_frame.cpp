#include "gvdp/tiles/tiled_frame.h"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <string>

#include "gvdp/base/error.h"
#include "gvdp/tiles/tile_plan.h"

namespace gvdp::detail {

TileOptions::Mode parseTileMode(std::string_view text, int* grid) {
  if (text == "auto") return TileOptions::Mode::Auto;
  if (text == "off") return TileOptions::Mode::Off;
  int n = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
  GVDP_INPUT_CHECK(
      ec == std::errc() && end == text.data() + text.size() && n >= 1 && n <= MAX_TILE_GRID,
      "bad --tiles '", std::string(text), "' (expected auto, off or 1..", MAX_TILE_GRID, ")");
  *grid = n;
  return TileOptions::Mode::Grid;
}

namespace {

// Splits [0, n) into `parts` nearly equal spans; span i starts at startOf(i).
int startOf(int n, int parts, int i) {
  return static_cast<int>(static_cast<int64_t>(n) * i / parts);
}

void halveUntil(const PixelTile& t, int64_t maxPixels, std::vector<PixelTile>& out) {
  std::vector<PixelTile> quarters =
      t.pixels() > maxPixels ? splitTile(t) : std::vector<PixelTile>{};
  if (quarters.empty()) {
    out.push_back(t);
    return;
  }
  for (const PixelTile& q : quarters) halveUntil(q, maxPixels, out);
}

// An attempt whose image is replaced: its time and work count, its pixels do not.
void discard(FrameStats& s) {
  s.degraded = false;
  s.unfinishedPixels = 0;
  s.cache.coarser = 0;
}

void copyTile(const Image& tile, const PixelTile& at, Image& out) {
  for (int y = 0; y < at.height; ++y)
    std::memcpy(&out.pixels[static_cast<size_t>(at.y + y) * out.width + at.x],
                &tile.pixels[static_cast<size_t>(y) * tile.width],
                static_cast<size_t>(at.width) * sizeof(uint32_t));
}

// A kept tile's ray costs into the image's (sized at the first).
void copyTileCosts(RayCosts& tile, const PixelTile& at, int width, int height, RayCosts& out) {
  if (tile.empty()) return;
  if (at.x == 0 && at.y == 0 && at.width == width && at.height == height) {
    out = std::move(tile);
    return;
  }
  size_t n = static_cast<size_t>(width) * height;
  if (out.empty()) {
    out.width = width;
    out.height = height;
    out.lookups.assign(n, 0u);
    out.samples.assign(n, 0u);
    out.stops.assign(n, 0u);
  }
  for (int y = 0; y < at.height; ++y) {
    size_t to = static_cast<size_t>(at.y + y) * width + at.x,
           from = static_cast<size_t>(y) * at.width;
    std::copy_n(&tile.lookups[from], at.width, &out.lookups[to]);
    std::copy_n(&tile.samples[from], at.width, &out.samples[to]);
    std::copy_n(&tile.stops[from], at.width, &out.stops[to]);
  }
}

}  // namespace

std::vector<PixelTile> splitTile(const PixelTile& t) {
  bool splitX = t.width >= 2 * MIN_TILE_SIDE, splitY = t.height >= 2 * MIN_TILE_SIDE;
  if (!splitX && !splitY) return {};
  int w0 = splitX ? t.width / 2 : t.width, h0 = splitY ? t.height / 2 : t.height;
  std::vector<PixelTile> q;
  for (int j = 0; j < (splitY ? 2 : 1); ++j)
    for (int i = 0; i < (splitX ? 2 : 1); ++i)
      q.push_back(
          {t.x + i * w0, t.y + j * h0, i == 0 ? w0 : t.width - w0, j == 0 ? h0 : t.height - h0});
  return q;
}

std::vector<PixelTile> initialTiles(int width, int height, const TileOptions& o) {
  PixelTile whole{0, 0, width, height};
  std::vector<PixelTile> tiles;
  if (o.mode == TileOptions::Mode::Grid) {
    int nx = std::min(o.grid, std::max(1, width / MIN_TILE_SIDE));
    int ny = std::min(o.grid, std::max(1, height / MIN_TILE_SIDE));
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        PixelTile t{startOf(width, nx, i), startOf(height, ny, j), 0, 0};
        t.width = startOf(width, nx, i + 1) - t.x;
        t.height = startOf(height, ny, j + 1) - t.y;
        halveUntil(t, o.maxTilePixels, tiles);
      }
    return tiles;
  }
  GVDP_INPUT_CHECK(o.mode != TileOptions::Mode::Off || whole.pixels() <= o.maxTilePixels,
                   "bad size ", width, "x", height, " for --tiles off (at most ", o.maxTilePixels,
                   " pixels in one frame; use --tiles auto)");
  halveUntil(whole, o.maxTilePixels, tiles);
  return tiles;
}

void addTileStats(FrameStats& total, const FrameStats& t) {
  total.ms += t.ms;
  total.unfinishedPixels += t.unfinishedPixels;
  total.passes += t.passes;
  total.degraded = total.degraded || t.degraded;
  total.launches += t.launches;
  total.launchFailures += t.launchFailures;
  total.deferred += t.deferred;
  total.sweptPixels += t.sweptPixels;
  total.relaunchedRays += t.relaunchedRays;
  total.longestWaitList = std::max(total.longestWaitList, t.longestWaitList);
  total.spike = total.spike || t.spike;
  total.lookaheadClaims += t.lookaheadClaims;
  total.prefetchClaims += t.prefetchClaims;
  total.prefetchRays += t.prefetchRays;
  total.prefetchEntered += t.prefetchEntered;
  total.prefetchItems += t.prefetchItems;
  total.lodBias = std::max(total.lodBias, t.lodBias);
  total.tilePlans += t.tilePlans;
  total.planMs += t.planMs;
  CacheStats& c = total.cache;
  c.requested += t.cache.requested;
  c.produced += t.cache.produced;
  c.empty += t.cache.empty;
  c.clear += t.cache.clear;
  c.marked += t.cache.marked;
  c.failed += t.cache.failed;
  c.evicted += t.cache.evicted;
  c.resident = t.cache.resident;  // at the end of the last tile
  c.unsampled += t.cache.unsampled;
  c.prefetched += t.cache.prefetched;
  c.prefetchUnused += t.cache.prefetchUnused;
  c.refills += t.cache.refills;
  c.samples += t.cache.samples;
  c.lookups += t.cache.lookups;
  c.skips += t.cache.skips;
  c.coarser += t.cache.coarser;
  if (total.timeline.records.empty()) total.timeline = t.timeline;
}

namespace {

// A tile that overflows the pool and cannot be split: rendered again from an empty cache at LOD
// bias 0, 1, ... (render/lod.h: coarser levels, then a nearer far distance) until its bricks
// fit. The image is then the exact one of the finest bias whose bricks fit the pool, a function
// of the frame alone: the same on every run and for every scheduler, and coarser everywhere
// rather than holed where bricks were missing. Only a tile that overflows even at the last bias
// stays degraded as rendered. `spent` takes the attempts replaced.
FrameStats renderDegraded(Scheduler& scheduler, const FrameSetup& tile, Image& out,
                          FrameStats& spent) {
  FrameSetup f = tile;
  f.coldCache = true;
  for (f.lod.bias = 0;; ++f.lod.bias) {
    FrameStats s = scheduler.render(f, out);
    if (!s.degraded || f.lod.bias == f.lod.levels - 1 + MAX_FAR_BIAS) {
      s.lodBias = f.lod.bias;
      s.degraded = s.degraded || f.lod.bias > 0;
      if (f.lod.bias > 0) s.cache.coarser = static_cast<uint64_t>(f.pixelCount());
      return s;
    }
    discard(s);
    addTileStats(spent, s);
  }
}

}  // namespace

namespace {

struct PendingTile {
  PixelTile tile;
  bool planned;  // by the pre-pass (or a quadrant of such a tile): not planned again
};

// The plan of `region` of `frame` (pixels of the frame), its time added to `total`; empty when
// the pre-pass gave up or found the region one tile (then quadrants go on).
std::vector<PendingTile> planRegion(const Scheduler& scheduler, const FrameSetup& frame,
                                    const PixelTile& region, uint64_t poolBricks,
                                    const TileOptions& o, FrameStats& total) {
  TilePlan plan =
      planTiles(scheduler, tileOf(frame, region.x, region.y, region.width, region.height),
                poolBricks, o.maxTilePixels);
  ++total.tilePlans;
  double ms = plan.map.ms + plan.subdivideMs;
  total.planMs += ms;
  total.ms += ms;
  std::vector<PendingTile> tiles;
  if (plan.tiles.size() < 2) return tiles;
  for (auto it = plan.tiles.rbegin(); it != plan.tiles.rend(); ++it)
    tiles.push_back({{region.x + it->x, region.y + it->y, it->width, it->height}, true});
  return tiles;
}

// Whether the frame starts from `memory`'s tiles (false: afresh), counting the frame.
bool startsFromMemory(TileMemory& memory, const FrameSetup& frame) {
  if (memory.width != frame.width || memory.height != frame.height) memory = {};
  if (memory.tiles.empty() || memory.left == 0) return false;
  --memory.left;
  return true;
}

// `memory` after a frame that started from it (`remembered`) or afresh, `splits` of its renders
// discarded, `kept` its tiles.
void remember(TileMemory& memory, const FrameSetup& frame, bool remembered, int splits,
              std::vector<PixelTile> kept) {
  memory.width = frame.width;
  memory.height = frame.height;
  if (!remembered) {
    memory.period = splits == 0 ? 0 : std::min(std::max(2 * memory.period, 4), MAX_TILE_REUSE);
    memory.left = memory.period;
  }
  if (memory.period == 0) kept.clear();
  memory.tiles = std::move(kept);
}

}  // namespace

FrameStats renderTiled(Scheduler& scheduler, const FrameSetup& frame, Image& out,
                       const TileOptions& o, uint64_t poolBricks, const TileProgress& progress,
                       TileMemory* memory) {
  bool split = o.mode != TileOptions::Mode::Off;
  bool plans = split && o.plan && poolBricks > 0;
  FrameStats total;
  total.index = frame.frameIndex;
  total.tiles = 0;
  // Depth first, in order (a stack, the first tile last): a tile that overflows is replaced by
  // its plan or its quadrants. The whole image renders into `out` itself: a frame that fits
  // costs nothing more.
  std::vector<PendingTile> todo;
  const bool remembered = memory && split && startsFromMemory(*memory, frame);
  std::vector<PixelTile> initial =
      remembered ? memory->tiles : initialTiles(frame.width, frame.height, o);
  for (auto it = initial.rbegin(); it != initial.rend(); ++it) todo.push_back({*it, remembered});
  std::vector<PixelTile> kept;
  int done = 0;
  Image image;
  while (!todo.empty()) {
    PendingTile pending = todo.back();
    todo.pop_back();
    const PixelTile& t = pending.tile;
    bool isWhole = t.pixels() == frame.pixelCount();
    Image& target = isWhole ? out : image;
    FrameSetup tile = tileOf(frame, t.x, t.y, t.width, t.height);
    FrameStats s = scheduler.render(tile, target);
    if (s.degraded) {
      discard(s);
      addTileStats(total, s);
      std::vector<PendingTile> next;
      if (plans && !pending.planned) next = planRegion(scheduler, frame, t, poolBricks, o, total);
      if (next.empty() && split) {
        std::vector<PixelTile> quarters = splitTile(t);
        for (auto it = quarters.rbegin(); it != quarters.rend(); ++it) next.push_back({*it, true});
      }
      if (!next.empty()) {
        ++total.tileSplits;
        todo.insert(todo.end(), next.begin(), next.end());
        continue;
      }
      s = renderDegraded(scheduler, tile, target, total);
    }
    if (!isWhole) {
      if (out.width != frame.width || out.height != frame.height)
        out = Image(frame.width, frame.height);
      copyTile(image, t, out);
    }
    ++total.tiles;
    ++done;
    kept.push_back(t);
    copyTileCosts(s.rayCosts, t, frame.width, frame.height, total.rayCosts);
    addTileStats(total, s);
    if (progress) progress(done, done + static_cast<int>(todo.size()));
  }
  if (memory && split) remember(*memory, frame, remembered, total.tileSplits, std::move(kept));
  return total;
}

}  // namespace gvdp::detail
