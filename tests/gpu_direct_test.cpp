// GPU tests: skipped at run time when no CUDA device is present.
#include <gtest/gtest.h>

#include "gvdp/bench/sequence.h"
#include "test_util.h"

namespace gvdp::detail {

class GpuDirectTest : public ::testing::TestWithParam<int> {};

// The CUDA direct renderer runs the same body as the CPU one; only floating-point contraction
// differs, so the images agree closely (PSNR >= 40 dB at 320x200).
TEST_P(GpuDirectTest, MatchesTheCpuRender) {
  GVDP_REQUIRE_GPU();
  SequenceOptions o;
  o.scene = std::string(allScenes()[GetParam()].name);
  o.width = 320;
  o.height = 200;
  o.frames = 1;
  o.scheduler.kind = SchedulerKind::Direct;
  Image cpu, gpu;
  o.scheduler.backend = Backend::Cpu;
  renderSequence(o, [&](const Image& im, const FrameStats&) { cpu = im; });
  o.scheduler.backend = Backend::Cuda;
  renderSequence(o, [&](const Image& im, const FrameStats&) { gpu = im; });
  double db = psnr(cpu, gpu);
  std::printf("[ measure ] %s direct cpu vs cuda 320x200: PSNR %.2f dB\n", o.scene.c_str(), db);
  EXPECT_GE(db, 40.0);
}

INSTANTIATE_TEST_SUITE_P(AllScenes, GpuDirectTest, ::testing::Range(0, SCENE_COUNT));

}  // namespace gvdp::detail
