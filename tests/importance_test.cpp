// The importance pre-pass (sched/importance_map.h) and the tiles planned from it
// (tiles/tile_plan.h): at one ray per pixel it counts the bricks a frame from an empty cache
// produces; its counts nest as a quadtree's should; its table grows until the keys fit; planned
// tiles cover the frame once within the capacity, and frames rendered from plans are exact with
// fewer discarded renders than quadrants alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "gvdp/bench/sequence.h"
#include "gvdp/tiles/tile_plan.h"
#include "test_util.h"

namespace gvdp::detail {
namespace {

struct Case {
  const char* scene;
  Movement movement;
};
constexpr Case CASES[] = {{"forest", Movement::Backward}, {"perlin", Movement::Walkthrough}};

SequenceOptions optionsFor(const Case& c, Backend backend, int w, int h) {
  SequenceOptions o;
  o.scene = c.scene;
  o.movement = c.movement;
  o.width = w;
  o.height = h;
  o.scheduler.backend = backend;
  return o;
}

// At stride 1 the pre-pass's rays are the frame's: its root counts the bricks that take slots,
// which a frame from an empty cache (a pool that holds it) produces. Equal up to the rays whose
// last samples differ between the direct and the cached march (quantised bricks).
void strideOneCountsWhatAColdFrameProduces(Backend backend, int w, int h) {
  for (const Case& c : CASES) {
    SequenceOptions o = optionsFor(c, backend, w, h);
    std::unique_ptr<Scheduler> s = test::schedulerFor(o);
    FrameSetup f = frameOf(o, 0);
    ImportanceOptions one;
    one.stride = 1;
    ImportanceMap m = s->importance(f, one);
    ASSERT_EQ(m.failure, nullptr);
    Image image;
    FrameStats st = s->render(f, image);
    ASSERT_FALSE(st.degraded);
    double produced = static_cast<double>(st.cache.produced);
    EXPECT_GT(produced, 100.0) << c.scene;
    EXPECT_NEAR(m.root(), produced, 0.02 * produced) << c.scene;
    ImportanceMap four = s->importance(f, {});
    std::printf(
        "[ measure ] %s %s %dx%d: produced %.0f, pre-pass root stride 1: %u, stride 4: %u "
        "(%.1f ms)\n",
        c.scene, std::string(backendName(backend)).c_str(), w, h, produced, m.root(), four.root(),
        four.ms);
  }
}

TEST(ImportanceCpu, StrideOneCountsTheBricksAColdFrameProduces) {
  strideOneCountsWhatAColdFrameProduces(Backend::Cpu, 96, 60);
}

TEST(ImportanceGpu, StrideOneCountsTheBricksAColdFrameProduces) {
  GVDP_REQUIRE_GPU();
  strideOneCountsWhatAColdFrameProduces(Backend::Cuda, 1500, 1000);
}

// A node's bricks: at least each child's (its set holds theirs), at most their sum.
void expectNested(const ImportanceMap& m) {
  ASSERT_EQ(m.counts.size(), mipmapSize(m.levels));
  for (int d = 0; d < m.levels; ++d)
    for (int y = 0; y < (1 << d); ++y)
      for (int x = 0; x < (1 << d); ++x) {
        uint32_t node = m.counts[mipmapIndex(d, x, y)], largest = 0;
        uint64_t sum = 0;
        for (int k = 0; k < 4; ++k) {
          uint32_t c = m.counts[mipmapIndex(d + 1, 2 * x + k % 2, 2 * y + k / 2)];
          largest = std::max(largest, c);
          sum += c;
        }
        ASSERT_GE(node, largest) << "depth " << d << " node " << x << "," << y;
        ASSERT_LE(node, sum) << "depth " << d << " node " << x << "," << y;
      }
}

TEST(ImportanceCpu, NodeCountsNestAndTheTableGrowsUntilTheKeysFit) {
  SequenceOptions o = optionsFor(CASES[0], Backend::Cpu, 100, 70);
  std::unique_ptr<Scheduler> s = test::schedulerFor(o);
  FrameSetup f = frameOf(o, 0);
  ImportanceMap m = s->importance(f, {});
  ASSERT_EQ(m.failure, nullptr);
  EXPECT_EQ(m.attempts, 1);
  EXPECT_EQ(m.blocksX, 7);
  EXPECT_EQ(m.blocksY, 5);
  EXPECT_EQ(m.levels, 3);
  expectNested(m);
  ImportanceOptions small;
  small.firstTableEntries = 64;
  ImportanceMap grown = s->importance(f, small);
  EXPECT_GT(grown.attempts, 2);
  EXPECT_EQ(grown.counts, m.counts);
  small.maxTableBytes = 4096;
  ImportanceMap none = s->importance(f, small);
  EXPECT_NE(none.failure, nullptr);
  EXPECT_TRUE(none.counts.empty());
  for (ImportanceOptions bad : {ImportanceOptions{16, 0}, ImportanceOptions{16, 3},
                                ImportanceOptions{2, 4}, ImportanceOptions{16, 4, 100}})
    EXPECT_THROW(s->importance(f, bad), InputError)
        << bad.blockPixels << " " << bad.stride << " " << bad.firstTableEntries;
}

// Planned tiles: the frame covered exactly once, each tile's count within the capacity (a
// single block may not be: flagged by its count alone), and what the tiles count is at least
// the frame's count (a brick seen from two tiles counts in both).
TEST(TilePlanCpu, PlannedTilesCoverTheFrameOnceWithinTheCapacity) {
  SequenceOptions o = optionsFor(CASES[0], Backend::Cpu, 160, 100);
  std::unique_ptr<Scheduler> s = test::schedulerFor(o);
  FrameSetup f = frameOf(o, 0);
  for (uint64_t pool : {uint64_t{400}, uint64_t{2000}, uint64_t{1} << 20}) {
    TilePlan plan = planTiles(*s, f, pool, 8 << 20);
    ASSERT_FALSE(plan.tiles.empty());
    std::vector<int> hits(static_cast<size_t>(f.width) * f.height, 0);
    uint64_t counted = 0, capacity = pool * PLAN_CAPACITY_NUM / PLAN_CAPACITY_DEN;
    for (const PlannedTile& t : plan.tiles) {
      for (int y = t.y; y < t.y + t.height; ++y)
        for (int x = t.x; x < t.x + t.width; ++x) ++hits[static_cast<size_t>(y) * f.width + x];
      bool oneBlock = t.width <= plan.map.blockPixels && t.height <= plan.map.blockPixels;
      if (!oneBlock) {
        EXPECT_LE(t.bricks, capacity) << "pool " << pool;
      }
      counted += t.bricks;
    }
    for (int h : hits) ASSERT_EQ(h, 1);
    EXPECT_GE(counted, plan.map.root());
    if (pool == uint64_t{1} << 20) {
      EXPECT_EQ(plan.tiles.size(), 1u);
    }
    std::printf("[ measure ] forest backward 160x100 pool %llu: %zu planned tiles, root %u\n",
                static_cast<unsigned long long>(pool), plan.tiles.size(), plan.map.root());
  }
}

// The case on the CPU: frames whose bricks do not fit the pool, rendered from plans and
// from quadrants alone: both exact, the plans discarding fewer renders.
TEST(TiledCpu, PlansDiscardFewerRendersThanQuadrants) {
  constexpr int FRAMES = 2, W = 160, H = 100;
  SchedulerOptions sp{Backend::Cpu, SchedulerKind::Sp, 600};
  TileOptions plans, quadrants;
  plans.plan = true;
  test::Renders large = test::renderRun("forest", {Backend::Cpu, SchedulerKind::Sp, 0}, FRAMES, W,
                                        H, Movement::Backward);
  test::Renders planned = test::renderRun("forest", sp, FRAMES, W, H, Movement::Backward, plans);
  test::Renders split = test::renderRun("forest", sp, FRAMES, W, H, Movement::Backward, quadrants);
  int plannedSplits = 0, quadrantSplits = 0;
  for (int f = 0; f < FRAMES; ++f) {
    EXPECT_EQ(planned.images[f].pixels, large.images[f].pixels) << "frame " << f;
    EXPECT_EQ(split.images[f].pixels, large.images[f].pixels) << "frame " << f;
    // The second frame starts from the tiles the first kept (TileMemory): nothing to plan.
    EXPECT_EQ(planned.stats[f].tilePlans > 0, f == 0) << "frame " << f;
    EXPECT_EQ(split.stats[f].tilePlans, 0);
    plannedSplits += planned.stats[f].tileSplits;
    quadrantSplits += split.stats[f].tileSplits;
  }
  EXPECT_LT(plannedSplits, quadrantSplits);
  std::printf(
      "[ measure ] forest backward %dx%d pool 600: renders discarded, planned %d, "
      "quadrants %d\n",
      W, H, plannedSplits, quadrantSplits);
}

}  // namespace
}  // namespace gvdp::detail
