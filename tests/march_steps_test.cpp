// Rays that yield after SchedulerOptions::marchSteps steps (render/march.h) go on later in tasks of
// other yielded rays: sp in its next pass, pt from its ray queue. Where a march yields changes
// when work is done, never the image.
#include <gtest/gtest.h>

#include "test_util.h"

namespace gvdp::detail {

using test::renderRun;
using test::Renders;
using test::sceneName;

namespace {

SchedulerOptions withSteps(Backend backend, SchedulerKind kind, uint32_t steps) {
  SchedulerOptions o{backend, kind};
  o.marchSteps = steps;
  return o;
}

// sp and pt with rays yielding every `steps` render the frames of sp without yields; sp then
// runs more passes (the yielded rays' passes), pt more render tasks.
void expectYieldsChangeNoImage(Backend backend, const std::string& scene, int frames, int w,
                               int h, uint32_t steps) {
  Renders sp = renderRun(scene, {backend, SchedulerKind::Sp}, frames, w, h);
  Renders pt = renderRun(scene, withSteps(backend, SchedulerKind::Pt, 0), frames, w, h);
  for (SchedulerKind kind : {SchedulerKind::Sp, SchedulerKind::Pt}) {
    Renders r = renderRun(scene, withSteps(backend, kind, steps), frames, w, h);
    const Renders& unyielded = kind == SchedulerKind::Sp ? sp : pt;
    int morePasses = 0, moreTasks = 0;
    for (int f = 0; f < frames; ++f) {
      EXPECT_EQ(sp.images[f].pixels, r.images[f].pixels)
          << scene << " " << schedulerName(kind) << " steps " << steps << " frame " << f;
      EXPECT_EQ(r.stats[f].unfinishedPixels, 0);
      EXPECT_FALSE(r.stats[f].degraded);
      morePasses += r.stats[f].passes > unyielded.stats[f].passes;
      moreTasks += r.stats[f].launches > unyielded.stats[f].launches;
    }
    if (kind == SchedulerKind::Sp)
      EXPECT_GT(morePasses, 0) << scene << ": yielded rays take passes of their own";
    else
      EXPECT_GT(moreTasks, 0) << scene << ": yielded rays take render tasks of their own";
  }
}

}  // namespace

class MarchStepsCpuTest : public ::testing::TestWithParam<int> {};

TEST_P(MarchStepsCpuTest, YieldingRaysChangeNoImage) {
  for (uint32_t steps : {3u, 40u})
    expectYieldsChangeNoImage(Backend::Cpu, sceneName(GetParam()), 6, 48, 32, steps);
}

INSTANTIATE_TEST_SUITE_P(AllScenes, MarchStepsCpuTest, ::testing::Range(0, SCENE_COUNT));

class MarchStepsGpuTest : public ::testing::TestWithParam<int> {};

TEST_P(MarchStepsGpuTest, YieldingRaysChangeNoImage) {
  GVDP_REQUIRE_GPU();
  for (uint32_t steps : {5u, 48u})
    expectYieldsChangeNoImage(Backend::Cuda, sceneName(GetParam()), 20, 320, 200, steps);
}

INSTANTIATE_TEST_SUITE_P(AllScenes, MarchStepsGpuTest, ::testing::Range(0, SCENE_COUNT));

}  // namespace gvdp::detail
