#include <gtest/gtest.h>

#include <cmath>

#include "gvdp/bench/sequence.h"
#include "gvdp/render/shade.h"

namespace gvdp {

namespace {
Image renderOne(const std::string& scene, int w, int h, Vec3d origin = {0, 0, 0}, int frame = 0) {
  SequenceOptions o;
  o.scene = scene;
  o.width = w;
  o.height = h;
  o.origin = origin;
  o.scheduler.kind = SchedulerKind::Direct;
  std::unique_ptr<Scheduler> s = makeScheduler(o.scheduler);
  Image image;
  FrameStats stats = s->render(frameOf(o, frame), image);
  EXPECT_EQ(stats.unfinishedPixels, 0);
  return image;
}
}  // namespace

class RenderTest : public ::testing::TestWithParam<int> {};

// Every scene renders something a person would call a picture: matter covers a real part of the
// image, sky or distance shows somewhere, and the pixels vary.
TEST_P(RenderTest, DirectRenderIsNotDegenerate) {
  std::string scene(allScenes()[GetParam()].name);
  Image image = renderOne(scene, 64, 40);
  SequenceOptions o;
  o.scene = scene;
  o.width = 64;
  o.height = 40;
  FrameSetup f = frameOf(o, 0);
  int covered = 0;
  double mean = 0.0, var = 0.0;
  for (int i = 0; i < f.pixelCount(); ++i) {
    Rgba8 sky = resolvePixel({0, 0, 0, 0}, f.primaryRay(i % f.width, i / f.width).d);
    covered += image.pixels[i] != sky;
    mean += (image.pixels[i] >> 8) & 255u;
  }
  mean /= f.pixelCount();
  for (uint32_t p : image.pixels) var += std::pow(((p >> 8) & 255u) - mean, 2.0);
  EXPECT_GT(covered, f.pixelCount() / 5) << scene << ": too little matter in view";
  EXPECT_GT(std::sqrt(var / f.pixelCount()), 8.0) << scene << ": flat image";
}

INSTANTIATE_TEST_SUITE_P(AllScenes, RenderTest, ::testing::Range(0, SCENE_COUNT));

// Positions are relative to a local origin: the periodic aligned-spheres world shifted by a
// million units (a whole number of periods and coarsest bricks) renders the very same image.
TEST(Render, AMillionUnitsFromTheOriginLooksTheSame) {
  Image near = renderOne("aligned-spheres", 48, 32);
  Image far = renderOne("aligned-spheres", 48, 32, {999936.0, 0.0, -999936.0});
  EXPECT_EQ(near.pixels, far.pixels);
}

TEST(Render, SameFrameTwiceIsIdentical) {
  EXPECT_EQ(renderOne("forest", 40, 24, {0, 0, 0}, 3).pixels,
            renderOne("forest", 40, 24, {0, 0, 0}, 3).pixels);
}

}  // namespace gvdp
