#include <gtest/gtest.h>

#include "gvdp/bench/sequence.h"
#include "test_util.h"

namespace gvdp::detail {

using test::Renders;

namespace {
Renders renderRun(const std::string& scene, SchedulerKind kind, Backend backend, int frames, int w,
                  int h, uint32_t poolBricks = 0, Movement movement = Movement::Walkthrough) {
  return test::renderRun(scene, {backend, kind, poolBricks}, frames, w, h, movement);
}
}  // namespace

class SpTest : public ::testing::TestWithParam<int> {
 protected:
  std::string scene() const { return std::string(allScenes()[GetParam()].name); }
};

// The cache holds exactly what direct evaluates on the fly: on the CPU (same trilinear code,
// producers conservative) the images agree; the bar is 45 dB.
TEST_P(SpTest, MatchesDirectOnAWalkthrough) {
  Renders sp = renderRun(scene(), SchedulerKind::Sp, Backend::Cpu, 3, 96, 60);
  Renders direct = renderRun(scene(), SchedulerKind::Direct, Backend::Cpu, 3, 96, 60);
  for (int f = 0; f < 3; ++f) {
    double db = psnr(sp.images[f], direct.images[f]);
    std::printf("[ measure ] %s frame %d sp vs direct (cpu, 96x60): PSNR %.2f dB\n",
                scene().c_str(), f, db);
    EXPECT_GE(db, 45.0) << scene() << " frame " << f;
    EXPECT_EQ(sp.stats[f].unfinishedPixels, 0);
    EXPECT_FALSE(sp.stats[f].degraded);
    EXPECT_GE(sp.stats[f].passes, 2) << "a first frame needs production";
  }
  EXPECT_GT(sp.stats[0].cache.produced, 0u);
}

TEST_P(SpTest, IsDeterministic) {
  Renders a = renderRun(scene(), SchedulerKind::Sp, Backend::Cpu, 3, 64, 40);
  Renders b = renderRun(scene(), SchedulerKind::Sp, Backend::Cpu, 3, 64, 40);
  for (int f = 0; f < 3; ++f) EXPECT_EQ(a.images[f].pixels, b.images[f].pixels) << "frame " << f;
}

// A pool far smaller than a frame's working set: every frame completes, degraded.
TEST_P(SpTest, TinyPoolDegradesButFinishesEveryPixel) {
  Renders r = test::schedulerRun(scene(), {Backend::Cpu, SchedulerKind::Sp, 64}, 3, 96, 60);
  for (const FrameStats& s : r.stats) {
    EXPECT_EQ(s.unfinishedPixels, 0);
    EXPECT_TRUE(s.degraded);
    EXPECT_LE(s.cache.resident, 64u);
  }
}

INSTANTIATE_TEST_SUITE_P(AllScenes, SpTest, ::testing::Range(0, SCENE_COUNT));

// A still camera: the same frame rendered again gives the same image and soon produces nothing.
// The second render may produce a few bricks: the CLEAR boxes grown after the first (cache/
// table_boxes.h) lead some rays to land in bricks they skipped before inside another brick's EMPTY
// box, never produced (random-spheres at 64x40: 10, then none).
TEST(Sp, StillCameraProducesNothingAfterTheFirstFrames) {
  SequenceOptions o;
  o.scene = "random-spheres";
  o.width = 64;
  o.height = 40;
  o.scheduler = {Backend::Cpu, SchedulerKind::Sp};
  std::unique_ptr<Scheduler> s = test::schedulerFor(o);
  FrameSetup frame = frameOf(o, 0);
  Image first, again;
  FrameStats a = s->render(frame, first);
  EXPECT_GT(a.cache.produced, 0u);
  uint32_t requested = 0;
  for (int k = 1; k <= 3; ++k) {
    FrameStats b = s->render(frame, again);
    EXPECT_EQ(first.pixels, again.pixels) << "render " << k;
    EXPECT_EQ(b.unfinishedPixels, 0);
    EXPECT_LT(b.cache.requested, a.cache.requested / 10) << "render " << k;
    requested = b.cache.requested;
  }
  EXPECT_EQ(requested, 0u) << "a still camera still producing at its fourth render";
}

// A moving camera reuses most of the cache: later frames produce fewer bricks than the first.
TEST(Sp, CacheCarriesOverFrames) {
  Renders r = renderRun("aligned-spheres", SchedulerKind::Sp, Backend::Cpu, 3, 64, 40, 0,
                        Movement::Forward);
  EXPECT_LT(r.stats[2].cache.produced, r.stats[0].cache.produced);
}

class GpuSpTest : public ::testing::TestWithParam<int> {};

TEST_P(GpuSpTest, MatchesCpuSp) {
  GVDP_REQUIRE_GPU();
  std::string scene(allScenes()[GetParam()].name);
  Renders cpu = renderRun(scene, SchedulerKind::Sp, Backend::Cpu, 3, 320, 200);
  Renders gpu = renderRun(scene, SchedulerKind::Sp, Backend::Cuda, 3, 320, 200);
  Renders gpuDirect = renderRun(scene, SchedulerKind::Direct, Backend::Cuda, 1, 320, 200);
  for (int f = 0; f < 3; ++f) {
    double db = psnr(cpu.images[f], gpu.images[f]);
    std::printf("[ measure ] %s frame %d sp cpu vs cuda 320x200: PSNR %.2f dB\n", scene.c_str(), f,
                db);
    EXPECT_GE(db, 40.0);
    EXPECT_EQ(gpu.stats[f].unfinishedPixels, 0);
  }
  double db = psnr(gpu.images[0], gpuDirect.images[0]);
  std::printf("[ measure ] %s sp cuda vs direct cuda 320x200: PSNR %.2f dB\n", scene.c_str(), db);
  EXPECT_GE(db, 45.0) << "the cache holds what direct evaluates (the CPU bar, SpTest)";
}

TEST_P(GpuSpTest, TinyPoolFinishesEveryPixel) {
  GVDP_REQUIRE_GPU();
  Renders r = test::schedulerRun(std::string(allScenes()[GetParam()].name),
                                 {Backend::Cuda, SchedulerKind::Sp, 64}, 3, 320, 200);
  for (const FrameStats& s : r.stats) {
    EXPECT_EQ(s.unfinishedPixels, 0);
    EXPECT_TRUE(s.degraded);
  }
}

INSTANTIATE_TEST_SUITE_P(AllScenes, GpuSpTest, ::testing::Range(0, SCENE_COUNT));

}  // namespace gvdp::detail
