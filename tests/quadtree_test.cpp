// The quadtree subdivision (src/gvdp/tiles/quadtree.h): the sum-mipmap against brute force, the
// reference's tiles against the rule's promises (an exact cover of the valid blocks, limits kept,
// maximal tiles, single blocks flagged), and every GPU method and L against the reference.
#include "gvdp/tiles/quadtree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <ostream>
#include <random>
#include <vector>

#include "gvdp/base/error.h"
#include "test_util.h"

namespace gvdp::detail {

// gtest's failure messages name tiles, not their bytes.
void PrintTo(const Tile& t, std::ostream* os) {
  *os << "{depth " << t.depth << " at " << t.x << "," << t.y << " sum " << t.sum
      << (t.overflows ? " overflows}" : "}");
}

namespace {

constexpr int64_t NO_PIXEL_LIMIT = std::numeric_limits<int64_t>::max();

struct Grid {
  int width, height;
  std::vector<uint32_t> values;
};

Grid randomGrid(int width, int height, uint32_t seed, uint32_t maxValue = 100) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<uint32_t> value(0, maxValue);
  Grid g{width, height, std::vector<uint32_t>(size_t(width) * height)};
  for (auto& v : g.values) v = value(rng);
  return g;
}

// A frame over terrain: the sky needs next to nothing, the ground more the nearer it is (lower
// rows), with a few peaks.
Grid frameGrid(int width, int height, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<uint32_t> noise(0, 3);
  Grid g{width, height, std::vector<uint32_t>(size_t(width) * height)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      uint32_t near = static_cast<uint32_t>(y * 40 / height);
      uint32_t v = y < height / 3 ? noise(rng) / 3 : near * near + noise(rng);
      if (noise(rng) == 0 && y > height / 2) v *= 4;
      g.values[size_t(y) * width + x] = v;
    }
  return g;
}

SumMipmap mipmapOf(const Grid& g) {
  return buildSumMipmap(g.values.data(), g.width, g.height);
}

// Image in pixels from the grid: blocks of `blockPixels`, the last column and row `trim` short.
SubdivisionParams paramsFor(const SumMipmap& m, uint64_t capacity, int64_t maxTilePixels,
                            int blockPixels = 8, int trim = 3) {
  SubdivisionParams p;
  p.capacity = capacity;
  p.maxTilePixels = maxTilePixels;
  p.blockPixels = blockPixels;
  p.imageWidth = m.width * blockPixels - trim;
  p.imageHeight = m.height * blockPixels - trim;
  return p;
}

// Sums of the padded grid over any square, from a summed-area table: independent of the mipmap.
struct BoxSums {
  int n;
  std::vector<uint64_t> table;  // (n + 1)^2
  BoxSums(const Grid& g, int levels) : n(1 << levels), table(size_t(n + 1) * (n + 1), 0) {
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        uint64_t v = x < g.width && y < g.height ? g.values[size_t(y) * g.width + x] : 0;
        at(x + 1, y + 1) = v + at(x, y + 1) + at(x + 1, y) - at(x, y);
      }
  }
  uint64_t& at(int x, int y) { return table[size_t(y) * (n + 1) + x]; }
  uint64_t node(int levels, int depth, int x, int y) {
    int s = 1 << (levels - depth);
    return at((x + 1) * s, (y + 1) * s) - at(x * s, (y + 1) * s) - at((x + 1) * s, y * s) +
           at(x * s, y * s);
  }
};

// Every promise of the rule, checked without decideNode: an exact cover of the valid blocks,
// nothing outside the image, limits kept (or a single block flagged), every tile maximal.
void expectValidTiling(const Grid& g, const SumMipmap& m, const SubdivisionParams& p,
                       const std::vector<Tile>& tiles) {
  BoxSums box(g, m.levels);
  std::vector<int> covered(size_t(g.width) * g.height, 0);
  auto pixels = [](const TileRect& r) { return int64_t{r.width} * r.height; };
  for (const Tile& t : tiles) {
    SCOPED_TRACE(::testing::Message() << "tile depth " << t.depth << " at " << t.x << "," << t.y);
    ASSERT_GE(t.depth, 0);
    ASSERT_LE(t.depth, m.levels);
    TileRect r = tileRect(t, m.levels, p);
    ASSERT_GT(r.width, 0);
    ASSERT_GT(r.height, 0);
    EXPECT_LE(r.x0 + r.width, p.imageWidth);
    EXPECT_LE(r.y0 + r.height, p.imageHeight);
    EXPECT_EQ(t.sum, box.node(m.levels, t.depth, t.x, t.y));
    bool fits = t.sum <= p.capacity && pixels(r) <= p.maxTilePixels;
    EXPECT_EQ(t.overflows, !fits);
    if (t.overflows) {
      EXPECT_EQ(t.depth, m.levels);
    }
    if (t.depth > 0) {  // maximal: the parent breaks a limit
      TileRect pr = nodePixelRect(m.levels, p, t.depth - 1, t.x / 2, t.y / 2);
      EXPECT_TRUE(box.node(m.levels, t.depth - 1, t.x / 2, t.y / 2) > p.capacity ||
                  pixels(pr) > p.maxTilePixels);
    }
    int side = 1 << (m.levels - t.depth);
    for (int y = t.y * side; y < std::min((t.y + 1) * side, g.height); ++y)
      for (int x = t.x * side; x < std::min((t.x + 1) * side, g.width); ++x)
        ++covered[size_t(y) * g.width + x];
  }
  EXPECT_EQ(std::count(covered.begin(), covered.end(), 1), int64_t(covered.size()))
      << "a valid block is covered other than once";
}

std::vector<Tile> sorted(std::vector<Tile> tiles, int levels) {
  sortCanonical(tiles, levels);
  return tiles;
}

TEST(Quadtree, LevelsPadToAPowerOfTwo) {
  EXPECT_EQ(quadtreeLevels(1, 1), 0);
  EXPECT_EQ(quadtreeLevels(37, 13), 6);
  EXPECT_EQ(quadtreeLevels(1000, 3), 10);
  EXPECT_EQ(quadtreeLevels(8192, 1), 13);
  EXPECT_THROW(quadtreeLevels(8193, 1), InputError);
  EXPECT_THROW(quadtreeLevels(0, 4), InputError);
}

TEST(Quadtree, MipmapSumsMatchBruteForce) {
  for (auto [w, h] : {std::pair{37, 13}, {1, 1}, {1000, 3}, {64, 64}, {5, 70}}) {
    SCOPED_TRACE(::testing::Message() << w << "x" << h);
    Grid g = randomGrid(w, h, 7u + w, 0xffffffffu);  // large values: sums past 32 bits
    SumMipmap m = mipmapOf(g);
    ASSERT_EQ(m.values.size(), mipmapSize(m.levels));
    BoxSums box(g, m.levels);
    for (int d = 0; d <= m.levels; ++d)
      for (int y = 0; y < (1 << d); ++y)
        for (int x = 0; x < (1 << d); ++x)
          ASSERT_EQ(m.view({}).sum(d, x, y), box.node(m.levels, d, x, y))
              << d << " " << x << "," << y;
  }
}

TEST(Quadtree, TilesAreAnExactMaximalCoverWithinTheLimits) {
  for (auto [w, h] : {std::pair{37, 13}, {1, 1}, {1000, 3}, {3, 200}, {128, 72}})
    for (uint32_t seed : {1u, 2u})
      for (uint64_t capacity : {uint64_t{0}, uint64_t{50}, uint64_t{400}, uint64_t{5000}})
        for (int64_t maxPixels : {NO_PIXEL_LIMIT, int64_t{40 * 40}}) {
          SCOPED_TRACE(::testing::Message() << w << "x" << h << " seed " << seed << " capacity "
                                            << capacity << " pixels " << maxPixels);
          Grid g = randomGrid(w, h, seed);
          SumMipmap m = mipmapOf(g);
          SubdivisionParams p = paramsFor(m, capacity, maxPixels);
          expectValidTiling(g, m, p, subdivide(m, p));
        }
}

TEST(Quadtree, FrameShapedMapTilesFinerNearTheBottom) {
  Grid g = frameGrid(160, 90, 3);
  SumMipmap m = mipmapOf(g);
  SubdivisionParams p = paramsFor(m, 2000, NO_PIXEL_LIMIT, 16, 0);
  std::vector<Tile> tiles = subdivide(m, p);
  expectValidTiling(g, m, p, tiles);
  int64_t top = 0, bottom = 0;  // tiles starting in the top and bottom thirds
  for (const Tile& t : tiles) {
    TileRect r = tileRect(t, m.levels, p);
    if (r.y0 < p.imageHeight / 3) ++top;
    if (r.y0 >= 2 * p.imageHeight / 3) ++bottom;
  }
  EXPECT_GT(bottom, 4 * top);
}

TEST(Quadtree, SingleBlocksPastALimitAreFlagged) {
  Grid g{4, 3, std::vector<uint32_t>(12, 1)};
  g.values[5] = 1000;  // block (1, 1)
  SumMipmap m = mipmapOf(g);
  SubdivisionParams p = paramsFor(m, 10, NO_PIXEL_LIMIT);
  std::vector<Tile> tiles = subdivide(m, p);
  expectValidTiling(g, m, p, tiles);
  auto flagged =
      std::count_if(tiles.begin(), tiles.end(), [](const Tile& t) { return t.overflows; });
  ASSERT_EQ(flagged, 1);
  auto it = std::find_if(tiles.begin(), tiles.end(), [](const Tile& t) { return t.overflows; });
  EXPECT_EQ(*it, (Tile{m.levels, 1, 1, 1000, true}));

  // A pixel limit under one block's pixels: every block is a tile, each flagged.
  p = paramsFor(m, 1u << 20, 8 * 8 - 1, 8, 0);
  tiles = subdivide(m, p);
  expectValidTiling(g, m, p, tiles);
  EXPECT_EQ(tiles.size(), 12u);
  for (const Tile& t : tiles) EXPECT_TRUE(t.overflows);
}

TEST(Quadtree, CapacityEdgeCases) {
  Grid g = randomGrid(37, 13, 5);
  for (auto& v : g.values) v += 1;  // every block needs something
  SumMipmap m = mipmapOf(g);
  // Capacity 0: every valid block alone, every one flagged.
  SubdivisionParams p = paramsFor(m, 0, NO_PIXEL_LIMIT);
  std::vector<Tile> tiles = subdivide(m, p);
  expectValidTiling(g, m, p, tiles);
  EXPECT_EQ(tiles.size(), size_t(37 * 13));
  // Huge capacity, no pixel limit: the root, clipped to the image.
  p = paramsFor(m, std::numeric_limits<uint64_t>::max(), NO_PIXEL_LIMIT);
  tiles = subdivide(m, p);
  ASSERT_EQ(tiles.size(), 1u);
  EXPECT_EQ(tiles[0].depth, 0);
  EXPECT_EQ(tileRect(tiles[0], m.levels, p), (TileRect{0, 0, p.imageWidth, p.imageHeight}));
  // Capacity 0 over zeros: empty regions still merge into large tiles.
  Grid zeros{37, 13, std::vector<uint32_t>(37 * 13, 0)};
  SumMipmap z = mipmapOf(zeros);
  p = paramsFor(z, 0, NO_PIXEL_LIMIT);
  tiles = subdivide(z, p);
  expectValidTiling(zeros, z, p, tiles);
  EXPECT_EQ(tiles.size(), 1u);
}

TEST(Quadtree, CanonicalOrderIsByRow) {
  Grid g = randomGrid(37, 13, 9);
  SumMipmap m = mipmapOf(g);
  SubdivisionParams p = paramsFor(m, 300, NO_PIXEL_LIMIT);
  std::vector<Tile> tiles = sorted(subdivide(m, p), m.levels);
  for (size_t i = 1; i < tiles.size(); ++i) {
    TileRect a = tileRect(tiles[i - 1], m.levels, p), b = tileRect(tiles[i], m.levels, p);
    EXPECT_TRUE(a.y0 < b.y0 || (a.y0 == b.y0 && a.x0 < b.x0));
  }
}

TEST(Quadtree, PlannedPassesFollowTheLevels) {
  Grid g = randomGrid(64, 64, 4);
  for (auto& v : g.values) v += 1;
  SumMipmap m = mipmapOf(g);
  ASSERT_EQ(m.levels, 6);
  // Capacity 0 over positive values: a full tree down to single blocks.
  SubdivisionParams p = paramsFor(m, 0, NO_PIXEL_LIMIT);
  SubdivisionStats s = plannedPasses(m, p, SubdivisionMethod::MultiPass);
  EXPECT_EQ(s.passes, 7);
  EXPECT_EQ(s.activeNodes, (std::vector<uint64_t>{1, 4, 16, 64, 256, 1024, 4096}));
  // A pass reaching depth K decides it: none starts there.
  EXPECT_EQ(plannedPasses(m, p, SubdivisionMethod::Subtree, 1).passes, 6);
  EXPECT_EQ(plannedPasses(m, p, SubdivisionMethod::Subtree, 2).activeNodes,
            (std::vector<uint64_t>{1, 16, 256}));
  EXPECT_EQ(plannedPasses(m, p, SubdivisionMethod::Subtree, 3).passes, 2);
  EXPECT_EQ(plannedPasses(m, p, SubdivisionMethod::Subtree, 6).passes, 1);
  EXPECT_EQ(plannedPasses(m, p, SubdivisionMethod::Subtree, 8).passes, 1);
  EXPECT_EQ(plannedPasses(m, p, SubdivisionMethod::Dynamic).deviceLaunches, (4096u - 1) / 3);
}

TEST(Quadtree, ParamsMustFitTheGrid) {
  Grid g = randomGrid(37, 13, 1);
  SumMipmap m = mipmapOf(g);
  SubdivisionParams p = paramsFor(m, 100, NO_PIXEL_LIMIT);
  p.imageWidth += 8;  // one block column more than the grid
  EXPECT_THROW(subdivide(m, p), InputError);
  p = paramsFor(m, 100, NO_PIXEL_LIMIT);
  p.blockPixels = 0;
  EXPECT_THROW(subdivide(m, p), InputError);
  EXPECT_THROW(plannedPasses(m, paramsFor(m, 1, 1), SubdivisionMethod::Subtree, 9), InputError);
}

TEST(Quadtree, GpuMethodsRefuseWithoutCuda) {
  if (cudaBuilt()) GTEST_SKIP() << "built with CUDA";
  Grid g = randomGrid(8, 8, 1);
  SumMipmap m = mipmapOf(g);
  EXPECT_THROW(subdivide(m, paramsFor(m, 10, NO_PIXEL_LIMIT), SubdivisionMethod::MultiPass),
               InputError);
  GpuQuadtree gpu;
  EXPECT_THROW(gpu.upload(g.values.data(), 8, 8, nullptr), InputError);
}

// --- GPU -------------------------------------------------------------------------------------

TEST(Quadtree, GpuMipmapMatchesCpu) {
  GVDP_REQUIRE_GPU();
  GpuQuadtree gpu;
  for (auto [w, h] : {std::pair{37, 13}, {1, 1}, {2, 1}, {1000, 3}, {128, 128}, {300, 257}}) {
    SCOPED_TRACE(::testing::Message() << w << "x" << h);
    Grid g = randomGrid(w, h, 11u + h, 0xffffffffu);
    gpu.upload(g.values.data(), w, h, nullptr);
    gpu.buildMipmap(nullptr);
    SumMipmap cpu = mipmapOf(g), dev = gpu.downloadMipmap(nullptr);
    EXPECT_EQ(dev.levels, cpu.levels);
    EXPECT_EQ(dev.values, cpu.values);
  }
}

// Every GPU method on one map: the reference's tiles, and the passes plannedPasses predicts.
void expectGpuMatchesCpu(GpuQuadtree& gpu, const Grid& g, const SubdivisionParams& p) {
  gpu.upload(g.values.data(), g.width, g.height, nullptr);
  gpu.buildMipmap(nullptr);
  SumMipmap m = mipmapOf(g);
  std::vector<Tile> expected = sorted(subdivide(m, p), m.levels);
  for (GpuSubdivision x : gpuSubdivisions()) {
    SCOPED_TRACE(::testing::Message() << methodName(x.method) << " L=" << x.levelsPerPass);
    SubdivisionStats stats;
    uint64_t count = gpu.run(p, x.method, x.levelsPerPass, nullptr, &stats);
    EXPECT_EQ(count, expected.size());
    EXPECT_EQ(sorted(gpu.tiles(nullptr), m.levels), expected);
    SubdivisionStats planned = plannedPasses(m, p, x.method, x.levelsPerPass);
    EXPECT_EQ(stats.passes, planned.passes);
    EXPECT_EQ(stats.activeNodes, planned.activeNodes);
    EXPECT_EQ(stats.deviceLaunches, planned.deviceLaunches);
  }
}

TEST(Quadtree, EveryGpuMethodMatchesCpuOnRandomMaps) {
  GVDP_REQUIRE_GPU();
  GpuQuadtree gpu;
  for (auto [w, h] : {std::pair{37, 13}, {1, 1}, {1000, 3}, {256, 144}, {5, 300}})
    for (uint32_t seed : {1u, 2u, 3u})
      for (uint64_t capacity : {uint64_t{0}, uint64_t{120}, uint64_t{3000}, uint64_t{1} << 40})
        for (int64_t maxPixels : {NO_PIXEL_LIMIT, int64_t{64 * 64}}) {
          SCOPED_TRACE(::testing::Message() << w << "x" << h << " seed " << seed << " capacity "
                                            << capacity << " pixels " << maxPixels);
          Grid g = randomGrid(w, h, seed);
          expectGpuMatchesCpu(gpu, g, paramsFor(mipmapOf(g), capacity, maxPixels));
        }
}

TEST(Quadtree, EveryGpuMethodMatchesCpuOnAFrameShapedMap) {
  GVDP_REQUIRE_GPU();
  GpuQuadtree gpu;
  Grid g = frameGrid(480, 270, 8);
  SumMipmap m = mipmapOf(g);
  for (uint64_t capacity : {uint64_t{100}, uint64_t{10000}, uint64_t{1000000}})
    expectGpuMatchesCpu(gpu, g, paramsFor(m, capacity, NO_PIXEL_LIMIT, 16, 0));
}

TEST(Quadtree, OneShotGpuSubdivideMatchesCpu) {
  GVDP_REQUIRE_GPU();
  Grid g = randomGrid(37, 13, 6);
  SumMipmap m = mipmapOf(g);
  SubdivisionParams p = paramsFor(m, 200, NO_PIXEL_LIMIT);
  EXPECT_EQ(sorted(subdivide(m, p, SubdivisionMethod::Subtree, 3), m.levels),
            sorted(subdivide(m, p), m.levels));
  if (!GVDP_CDP) {
    EXPECT_THROW(subdivide(m, p, SubdivisionMethod::Dynamic), InputError);
  }
}

}  // namespace
}  // namespace gvdp::detail
