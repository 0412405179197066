// Budget mode (--budget-ms, BrickCache::setBudget): past a frame's deadline a ray whose brick is
// not ready shows the nearest resident coarser level instead of waiting. Such a frame still
// finishes every pixel and counts the pixels shown coarser; the bricks are produced all the
// same, so once the camera stops the frames become exact: bit for bit the exact frame.
#include <gtest/gtest.h>

#include <cstdio>

#include "gvdp/bench/sequence.h"
#include "test_util.h"

namespace gvdp::detail {
namespace {

constexpr int MOVING_FRAMES = 4, MAX_STILL_FRAMES = 128;

SequenceOptions sequence(const std::string& scene, Backend backend, SchedulerKind kind) {
  SequenceOptions o;
  o.scene = scene;
  o.width = 96;
  o.height = 64;
  o.scheduler = {backend, kind};
  return o;
}

// Budget 0 (never wait): frames along the walkthrough, then the camera stops on the last pose.
void budgetFramesBecomeExact(const std::string& scene, Backend backend, SchedulerKind kind) {
  SequenceOptions o = sequence(scene, backend, kind);
  FrameSetup still = frameOf(o, MOVING_FRAMES - 1);
  Image exact, image;
  FrameStats e = test::schedulerFor(o)->render(still, exact);
  ASSERT_EQ(e.unfinishedPixels, 0);
  ASSERT_EQ(e.cache.coarser, 0u) << "an exact frame shows no coarser level";
  o.scheduler.budgetMs = 0.0;
  std::unique_ptr<Scheduler> s = test::schedulerFor(o);
  std::string name = scene + " " + std::string(schedulerName(kind));
  for (int f = 0; f < MOVING_FRAMES; ++f) {
    FrameStats st = s->render(frameOf(o, f), image);
    EXPECT_EQ(st.unfinishedPixels, 0) << name << " frame " << f;
    if (f == 0) {
      EXPECT_GT(st.cache.coarser, 0u) << name << ": the cold frame is flagged coarser";
    }
  }
  int stillFrames = 0;
  FrameStats st;
  do {
    st = s->render(still, image);
    EXPECT_EQ(st.unfinishedPixels, 0) << name << " still frame " << stillFrames;
    ++stillFrames;
  } while (st.cache.coarser != 0 && stillFrames < MAX_STILL_FRAMES);
  EXPECT_EQ(st.cache.coarser, 0u) << name << ": still coarser after " << stillFrames << " frames";
  EXPECT_EQ(image.pixels, exact.pixels) << name << ": a frame with nothing coarser is exact";
  std::printf("[ measure ] %s %s budget 0: exact after %d still frames\n", name.c_str(),
              std::string(backendName(backend)).c_str(), stillFrames);
}

// A budget no frame reaches changes nothing: the exact frames, none flagged.
void ampleBudgetIsExact(const std::string& scene, Backend backend, SchedulerKind kind) {
  SchedulerOptions exact{backend, kind};
  SchedulerOptions budgeted = exact;
  budgeted.budgetMs = MAX_BUDGET_MS;
  test::Renders a = test::renderRun(scene, exact, MOVING_FRAMES, 96, 64);
  test::Renders b = test::renderRun(scene, budgeted, MOVING_FRAMES, 96, 64);
  for (int f = 0; f < MOVING_FRAMES; ++f) {
    EXPECT_EQ(b.stats[f].cache.coarser, 0u) << scene << " frame " << f;
    EXPECT_EQ(a.images[f].pixels, b.images[f].pixels) << scene << " frame " << f;
  }
}

const SchedulerKind CPU_KINDS[] = {SchedulerKind::Sp, SchedulerKind::Dp, SchedulerKind::Pt};
const SchedulerKind GPU_KINDS[] = {SchedulerKind::Sp, SchedulerKind::Dp, SchedulerKind::Pt,
                                   SchedulerKind::Graph};

TEST(BudgetCpu, FramesUnderATinyBudgetFinishAndBecomeExactWhenTheCameraStops) {
  for (const char* scene : {"perlin", "forest"})
    for (SchedulerKind k : CPU_KINDS) budgetFramesBecomeExact(scene, Backend::Cpu, k);
}

TEST(BudgetCpu, AnAmpleBudgetRendersTheExactFrames) {
  for (SchedulerKind k : CPU_KINDS) ampleBudgetIsExact("random-spheres", Backend::Cpu, k);
}

TEST(BudgetGpu, FramesUnderATinyBudgetFinishAndBecomeExactWhenTheCameraStops) {
  GVDP_REQUIRE_GPU();
  for (const char* scene : {"perlin", "forest", "random-spheres"})
    for (SchedulerKind k : GPU_KINDS) budgetFramesBecomeExact(scene, Backend::Cuda, k);
}

TEST(BudgetGpu, AnAmpleBudgetRendersTheExactFrames) {
  GVDP_REQUIRE_GPU();
  for (SchedulerKind k : GPU_KINDS) ampleBudgetIsExact("random-spheres", Backend::Cuda, k);
}

}  // namespace
}  // namespace gvdp::detail
