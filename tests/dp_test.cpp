#include <gtest/gtest.h>

#include "gvdp/bench/sequence.h"
#include "gvdp/sched/dp/dp_body.h"
#include "test_util.h"

namespace gvdp::detail {

using test::renderRun;
using test::Renders;
using test::sceneName;

class DpCpuTest : public ::testing::TestWithParam<int> {};

// The main correctness test (docs/DESIGN.md): dp renders the very images sp renders.
TEST_P(DpCpuTest, MatchesSpBitForBitOnA20FrameWalkthrough) {
  Renders sp = renderRun(sceneName(GetParam()), {Backend::Cpu, SchedulerKind::Sp}, 20, 48, 32);
  Renders dp = renderRun(sceneName(GetParam()), {Backend::Cpu, SchedulerKind::Dp}, 20, 48, 32);
  for (int f = 0; f < 20; ++f) {
    EXPECT_EQ(sp.images[f].pixels, dp.images[f].pixels) << "frame " << f;
    EXPECT_EQ(dp.stats[f].unfinishedPixels, 0);
    EXPECT_EQ(dp.stats[f].sweptPixels, 0) << "the task schedule alone finishes every ray";
  }
  EXPECT_GT(dp.stats[0].launches, 0u);
}

INSTANTIATE_TEST_SUITE_P(AllScenes, DpCpuTest, ::testing::Range(0, SCENE_COUNT));

// A pending-launch buffer of 4: most launches are refused; the frame still completes (the sweep
// finishes the rays), the same picture, and the refusals are counted.
TEST(DpCpu, RefusedLaunchesDegradeNothingButAreCounted) {
  Renders sp = renderRun("perlin", {Backend::Cpu, SchedulerKind::Sp}, 2, 64, 40);
  Renders dp = renderRun("perlin", {Backend::Cpu, SchedulerKind::Dp, 0, 4}, 2, 64, 40);
  for (int f = 0; f < 2; ++f) {
    EXPECT_GT(dp.stats[f].launchFailures, 0u);
    EXPECT_EQ(dp.stats[f].unfinishedPixels, 0);
    EXPECT_EQ(sp.images[f].pixels, dp.images[f].pixels);
  }
}

TEST(DpCpu, TinyPoolDegradesButFinishesEveryPixel) {
  Renders dp = test::schedulerRun("forest", {Backend::Cpu, SchedulerKind::Dp, 64}, 3, 96, 60);
  for (const FrameStats& s : dp.stats) {
    EXPECT_EQ(s.unfinishedPixels, 0);
    EXPECT_TRUE(s.degraded);
  }
}

TEST(DpBody, BrickScreenRectHoldsThePixelsWhoseRaysCrossTheBrick) {
  SequenceOptions o;
  o.width = 64;
  o.height = 40;
  FrameSetup f = frameOf(o, 0);
  Clipmap c = clipmapOf(f);
  // March each pixel's ray a little and check its bricks' rectangles contain the pixel.
  int checked = 0;
  for (int py = 0; py < f.height; py += 3)
    for (int px = 0; px < f.width; px += 3) {
      Ray r = f.primaryRay(px, py);
      for (float t = 0.5f; t < 40.0f; t *= 1.3f) {
        for (int level = 0; level < 3; ++level) {
          Vec3f p = r.o + r.d * t;
          float side = f.lod.voxelSize(level) * BRICK_WIDTH;
          Vec3i local = floorToInt(p / side);
          BrickKey k{c.localOriginBrick[level] + local, level};
          PixelRect rect = brickScreenRect(f, c, k);
          ASSERT_TRUE(px >= rect.x0 && px < rect.x1 && py >= rect.y0 && py < rect.y1)
              << "pixel " << px << "," << py << " t " << t << " level " << level;
          ++checked;
        }
      }
    }
  EXPECT_GT(checked, 1000);
}

class GpuDpTest : public ::testing::TestWithParam<int> {};

TEST_P(GpuDpTest, MatchesGpuSpBitForBitOnA20FrameWalkthrough) {
  GVDP_REQUIRE_GPU();
  std::string scene = sceneName(GetParam());
  Renders sp = renderRun(scene, {Backend::Cuda, SchedulerKind::Sp}, 20, 320, 200);
  Renders dp = renderRun(scene, {Backend::Cuda, SchedulerKind::Dp}, 20, 320, 200);
  int64_t unfinished = 0, swept = 0, differing = 0;
  for (int f = 0; f < 20; ++f) {
    differing += sp.images[f].pixels != dp.images[f].pixels;
    EXPECT_EQ(sp.images[f].pixels, dp.images[f].pixels) << scene << " frame " << f;
    unfinished += dp.stats[f].unfinishedPixels;
    swept += dp.stats[f].sweptPixels;
  }
  std::printf(
      "[ measure ] %s dp vs sp cuda 320x200 x20: %lld differing frames, %lld unfinished, "
      "%lld swept pixels\n",
      scene.c_str(), static_cast<long long>(differing), static_cast<long long>(unfinished),
      static_cast<long long>(swept));
  EXPECT_EQ(unfinished, 0);
}

TEST_P(GpuDpTest, TinyPoolFinishesEveryPixel) {
  GVDP_REQUIRE_GPU();
  Renders a = test::schedulerRun(sceneName(GetParam()), {Backend::Cuda, SchedulerKind::Dp, 64}, 3,
                                 320, 200);
  for (const FrameStats& s : a.stats) {
    EXPECT_EQ(s.unfinishedPixels, 0);
    EXPECT_TRUE(s.degraded);
  }
}

// CUDA's pending-launch buffer set to 32 launches: a frame makes at most 16 device launches
// (its allowance, dp_kernels.cuh), the rest are refused, counted, and the sweep finishes their
// rays: the same images as sp, no pixel lost. (Before the allowance the device runtime refused
// them itself, and one run in 2-132 repeats of these 5 hung.)
TEST_P(GpuDpTest, TinyLaunchBufferRefusesLaunchesButMatchesSp) {
  GVDP_REQUIRE_GPU();
  std::string scene = sceneName(GetParam());
  Renders sp = renderRun(scene, {Backend::Cuda, SchedulerKind::Sp}, 3, 320, 200);
  Renders dp = renderRun(scene, {Backend::Cuda, SchedulerKind::Dp, 0, 32}, 3, 320, 200);
  EXPECT_GT(dp.stats[0].launchFailures, 0u) << "32 pending launches must overflow";
  for (int f = 0; f < 3; ++f) {
    EXPECT_LE(dp.stats[f].launches, 16u) << "half the buffer, never more";
    EXPECT_EQ(dp.stats[f].unfinishedPixels, 0);
    EXPECT_EQ(sp.images[f].pixels, dp.images[f].pixels) << scene << " frame " << f;
  }
}

INSTANTIATE_TEST_SUITE_P(AllScenes, GpuDpTest, ::testing::Range(0, SCENE_COUNT));

}  // namespace gvdp::detail
