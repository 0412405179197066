#include <gtest/gtest.h>

#include <random>

#include "gvdp/render/frame.h"
#include "gvdp/render/march.h"

namespace gvdp::detail {

TEST(Lod, LevelVoxelIsNeverSmallerThanTheConeFootprint) {
  Lod lod{1.0f / 16.0f, 2.0f * std::tan(0.5236f) / 1500.0f, 8};
  for (float t = 0.01f; t < lod.farDistance(); t *= 1.07f) {
    int level = lod.levelAt(t);
    ASSERT_LT(level, lod.levels);
    float footprint = t * lod.pixelAngle;
    EXPECT_LE(footprint, lod.voxelSize(level) * 1.0001f) << "t=" << t;
    if (level > 0) {
      EXPECT_GT(footprint, lod.voxelSize(level - 1) * 0.9999f) << "t=" << t;
    }
  }
  EXPECT_EQ(lod.levelAt(lod.farDistance() * 1.01f), lod.levels);
}

TEST(Lod, LatticeIsOneVoxelPerStepRestartingAtEachLevel) {
  Lod lod{0.0625f, 0.01f, 4};
  for (int level = 0; level < lod.levels; ++level) {
    EXPECT_FLOAT_EQ(lod.sampleT(level, 1) - lod.sampleT(level, 0), lod.voxelSize(level));
    EXPECT_GE(lod.sampleT(level, 0), lod.levelStart(level));
    if (level > 0) {
      EXPECT_FLOAT_EQ(lod.levelStart(level), lod.levelEnd(level - 1));
    }
    float t = lod.sampleT(level, 7);
    EXPECT_EQ(lod.firstStepAtOrAfter(level, t), 7);
    EXPECT_EQ(lod.firstStepAtOrAfter(level, t - 0.25f * lod.voxelSize(level)), 7);
    EXPECT_EQ(lod.firstStepAtOrAfter(level, t + 0.25f * lod.voxelSize(level)), 8);
  }
}

// firstStepAtOrAfter is exact: the first lattice sample at or after t (no sample before it is),
// whatever the voxel size (powers of two and not) and t (on samples, between, before the level).
// voxelSize is ldexpf's value.
TEST(Lod, FirstStepIsTheFirstSampleAtOrAfterT) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (float v0 : {0.0625f, 0.03125f, 0.1f, 0.0173f}) {
    Lod lod{v0, 0.0007f, 8};
    for (int level = 0; level < lod.levels; ++level) {
      EXPECT_EQ(lod.voxelSize(level), std::ldexp(v0, level));
      LevelSpan span = lod.span(level);
      for (int i = 0; i < 3000; ++i) {
        int k = static_cast<int>(u(rng) * 700.0f);
        float t = i % 3 == 0   ? span.sampleT(k)
                  : i % 3 == 1 ? std::nextafter(span.sampleT(k), 0.0f)
                               : span.start + (u(rng) * 700.0f - 2.0f) * span.voxelSize;
        int step = Lod::firstStepAtOrAfter(span, t);
        ASSERT_GE(span.sampleT(step), t) << v0 << " level " << level << " t " << t;
        if (step > 0) {
          ASSERT_LT(span.sampleT(step - 1), t) << v0 << " level " << level;
        }
      }
    }
  }
}

TEST(Lod, AdvanceAlwaysProgressesAndLandsOnTheLattice) {
  Lod lod{0.0625f, 0.02f, 5};
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 2000; ++i) {
    RayState s = initialRayState();
    s.level = static_cast<int>(u(rng) * lod.levels);
    s.step = static_cast<int>(u(rng) * 20);
    float before = lod.sampleT(s.level, s.step);
    float target = before + (u(rng) - 0.3f) * 3.0f;  // sometimes behind: must still progress
    RayState next = s;
    advanceTo(next, lod, lod.span(next.level), target);
    if (next.level >= lod.levels) continue;
    float after = lod.sampleT(next.level, next.step);
    EXPECT_GT(after, before);
    EXPECT_GE(after + 1e-4f, std::min(target, lod.levelEnd(next.level)));
  }
}

TEST(Lod, ClipmapWindowHoldsEverySampleOfItsLevel) {
  for (int width : {64, 160, 1500, 3840}) {
    float a = 2.0f * std::tan(0.5236f) / static_cast<float>(width);
    int w = clipmapWidthFor(a);
    Lod lod{0.0625f, a, 8};
    for (int level = 0; level < lod.levels; ++level) {
      // Farthest sample of the level, in bricks of that level, from the eye's brick.
      float reach = (lod.levelEnd(level) + lod.voxelSize(level)) / (8.0f * lod.voxelSize(level));
      EXPECT_LE(reach + 1.0f, static_cast<float>(w / 2)) << "width " << width << " level " << level;
    }
    if (width == 1500) {
      EXPECT_GT(w, 250);
      EXPECT_LT(w, 400);  // the paper's order of magnitude (300)
    }
  }
}

TEST(Frame, PrimaryRaysSpanTheFieldOfView) {
  FrameSetup f = makeFrame({{1e6, 5.0, -3e5}, 0.0f, 0.0f}, 0.0625f, 200, 100, 8, 0, 90.0f);
  Ray left = f.primaryRay(0, 50), right = f.primaryRay(199, 50), centre = f.primaryRay(100, 50);
  EXPECT_NEAR(std::acos(dot(left.d, right.d)), 0.5f * PI, 0.02f);
  EXPECT_GT(centre.d.z, 0.99f);
  // The eye is close to the local origin whatever the world position.
  EXPECT_LT(maxComponent(abs(f.eye)), 64.0f + 1e-3f);
  EXPECT_DOUBLE_EQ(f.localOrigin.x + f.eye.x, 1e6);
}

// The march's products by powers of two (Lod::reach0, inverseVoxelSize0) give the quotients'
// values exactly, for voxel sizes and angles that are not powers of two as well: the images
// cannot depend on which one is computed.
TEST(Lod, ProductsByPowersOfTwoGiveTheQuotientsValues) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (float v0 : {0.0625f, 1.0f / 1024.0f, 0.07f, 1.0f / 3.0f, 5.5f}) {
    for (int width : {160, 1500, 4096}) {
      Lod lod{v0, 2.0f * std::tan(0.5236f) / static_cast<float>(width), 10};
      for (int bias : {0, 3, 9, 14}) {
        lod.bias = bias;
        for (int level = 0; level < lod.levels; ++level) {
          float v = lod.voxelSize(level);
          int farBias = bias - (lod.levels - 1);
          float angle = level < lod.levels - 1 ? lod.levelAngle()
                        : farBias > 0          ? lod.pixelAngle * std::ldexp(1.0f, farBias)
                                               : lod.pixelAngle;
          EXPECT_EQ(lod.levelEnd(level), v / angle) << v0 << " level " << level << " bias " << bias;
          if (level > 0) {
            EXPECT_EQ(lod.levelStart(level), lod.voxelSize(level - 1) / lod.levelAngle());
          }
          EXPECT_EQ(lod.inverseVoxelSize(level), 1.0f / v);
          Vec3f p{(u(rng) - 0.5f) * 1e4f, u(rng) * 300.0f, (u(rng) - 0.5f) * 0.01f};
          Vec3f a = lod.inVoxels(p, level), b = p / v;
          EXPECT_TRUE(a.x == b.x && a.y == b.y && a.z == b.z);
          // A position's brick: the same as through the reciprocal of the brick's width.
          float bricksPerUnit = 1.0f / (v * 8.0f);
          EXPECT_TRUE(lod.span(level).brickOf(p) == floorToInt(p * bricksPerUnit));
        }
      }
    }
  }
}

}  // namespace gvdp::detail
