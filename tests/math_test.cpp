#include <gtest/gtest.h>

#include <random>

#include "gvdp/base/camera.h"
#include "gvdp/base/ray.h"

namespace gvdp::detail {

TEST(Math, FloorDivAndModMatchMathematicalDefinitions) {
  for (int a = -40; a <= 40; ++a)
    for (int b : {1, 3, 8, 300}) {
      int q = floorDiv(a, b), r = floorMod(a, b);
      EXPECT_EQ(q * b + r, a);
      EXPECT_GE(r, 0);
      EXPECT_LT(r, b);
    }
}

TEST(Math, HalfFloorAndExp2iAreTheirDefinitions) {
  for (int a = -40; a <= 40; ++a) {
    Vec3i h = halfFloor({a, -a, a + 1});
    EXPECT_EQ(h.x, floorDiv(a, 2));
    EXPECT_EQ(h.y, floorDiv(-a, 2));
    EXPECT_EQ(h.z, floorDiv(a + 1, 2));
  }
  for (int e = -126; e <= 127; ++e) EXPECT_EQ(exp2i(e), std::ldexp(1.0f, e)) << e;
}

// The planes are the faces of a box the ray leaves: the first it meets is the exit.
TEST(Math, PlanesExitLeavesABox) {
  Ray r{{0.5f, 0.5f, 0.5f}, normalize(Vec3f{1.0f, 0.0f, 0.0f})};
  EXPECT_FLOAT_EQ(planesExit(r, inverseDirection(r), {1, 1, 1}), 0.5f);
  Ray diag{{0, 0, 0}, normalize(Vec3f{1, 1, 1})};
  EXPECT_NEAR(planesExit(diag, inverseDirection(diag), {2, 2, 2}), 2.0f * std::sqrt(3.0f), 1e-5f);
  Ray neg{{0.25f, 0.5f, 0.5f}, {-1.0f, 0.0f, 0.0f}};
  EXPECT_FLOAT_EQ(planesExit(neg, inverseDirection(neg), {0, 1, 1}), 0.25f);
  Ray tilted{{0.5f, 0.5f, 0.5f}, normalize(Vec3f{1.0f, -2.0f, 0.5f})};
  float t = planesExit(tilted, inverseDirection(tilted), {1, 0, 1});  // leaves through y = 0
  EXPECT_NEAR(tilted.o.y + t * tilted.d.y, 0.0f, 1e-6f);
}

TEST(Math, NormalizeAndCross) {
  Vec3f n = normalize(Vec3f{3, 4, 12});
  EXPECT_NEAR(length(n), 1.0f, 1e-6f);
  Vec3f c = cross(Vec3f{1, 0, 0}, Vec3f{0, 1, 0});
  EXPECT_FLOAT_EQ(c.z, 1.0f);
}

TEST(Camera, BasisIsOrthonormalRightHandedAndUpright) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> yaw(-3.1f, 3.1f), pitch(-1.4f, 1.4f);
  for (int i = 0; i < 200; ++i) {
    CameraBasis b = cameraBasis({{0, 0, 0}, yaw(rng), pitch(rng)});
    EXPECT_NEAR(length(b.forward), 1.0f, 1e-5f);
    EXPECT_NEAR(length(b.right), 1.0f, 1e-5f);
    EXPECT_NEAR(length(b.up), 1.0f, 1e-5f);
    EXPECT_NEAR(dot(b.forward, b.right), 0.0f, 1e-5f);
    EXPECT_NEAR(dot(b.forward, b.up), 0.0f, 1e-5f);
    EXPECT_GT(b.up.y, 0.0f);
    EXPECT_NEAR(b.right.y, 0.0f, 1e-6f);  // no roll
  }
  // Yaw 0 looks along +z with +x on the left (right-handed, y up).
  CameraBasis b = cameraBasis({{0, 0, 0}, 0.0f, 0.0f});
  EXPECT_FLOAT_EQ(b.forward.z, 1.0f);
  EXPECT_FLOAT_EQ(b.right.x, -1.0f);
}

}  // namespace gvdp::detail
