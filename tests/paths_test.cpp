#include <gtest/gtest.h>

#include <cstdio>

#include "gvdp/base/error.h"
#include "gvdp/bench/paths.h"
#include "gvdp/render/frame.h"

namespace gvdp::detail {

namespace {
const CameraPose START{{10.0, 5.0, -3.0}, 0.4f, -0.1f};
double dist(Vec3d a, Vec3d b) {
  Vec3d d = a - b;
  return std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
}
}  // namespace

TEST(Paths, EveryMovementStartsAtTheStartAndFollowsItsPinnedPath) {
  const CameraPose PINNED[MOVEMENT_COUNT] = {
      {{19.815400943160057, 8.8451008119011991, 12.588230043649673}, 0.7155146f, -0.045307938f},
      {{17.204239174723625, 5, 14.039628118276596}, 0.4f, -0.1f},
      {{2.7957608252763748, 5, -20.039628118276596}, 0.4f, -0.1f},
      {{-7.0396281182765961, 5, 4.2042391747236252}, 0.4f, -0.1f},
      {{10, 5, -3}, 1.69499993f, -0.1f},
      {{-4.9377722703021805, 5, -9.1988262841861985}, 6.77582455f, -0.1f}};
  for (int m = 0; m < MOVEMENT_COUNT; ++m) {
    Movement mv = static_cast<Movement>(m);
    CameraPose p0 = cameraAt(mv, START, 0.5f, 0);
    EXPECT_NEAR(dist(p0.position, START.position), 0.0, 1e-12) << movementName(mv);
    if (mv != Movement::Orbit) {  // orbit looks at its axis
      EXPECT_FLOAT_EQ(p0.yaw, START.yaw);
    }
    // Frame 37 of every path as pinned here (BENCHMARKS.md compares commits on these paths).
    CameraPose a = cameraAt(mv, START, 0.5f, 37);
    std::printf("[ measure ] %s frame 37: {%.17g, %.17g, %.17g, %.9gf, %.9gf}\n",
                std::string(movementName(mv)).c_str(), a.position.x, a.position.y, a.position.z,
                a.yaw, a.pitch);
    EXPECT_EQ(a.position.x, PINNED[m].position.x) << movementName(mv);
    EXPECT_EQ(a.position.y, PINNED[m].position.y) << movementName(mv);
    EXPECT_EQ(a.position.z, PINNED[m].position.z) << movementName(mv);
    EXPECT_EQ(a.yaw, PINNED[m].yaw) << movementName(mv);
    EXPECT_EQ(a.pitch, PINNED[m].pitch) << movementName(mv);
    EXPECT_EQ(parseMovement(movementName(mv)), mv);
  }
}

TEST(Paths, OrbitCirclesTheVerticalAxisLookingAtIt) {
  for (int f : {0, 10, 200}) {
    CameraPose o = cameraAt(Movement::Orbit, START, 0.5f, f);
    EXPECT_NEAR(std::hypot(o.position.x, o.position.z),
                std::hypot(START.position.x, START.position.z), 1e-9);
    EXPECT_EQ(o.position.y, START.position.y);
    // Forward points at the axis: along -(x, z).
    double r = std::hypot(o.position.x, o.position.z);
    EXPECT_NEAR(std::sin(o.yaw), -o.position.x / r, 1e-6);
    EXPECT_NEAR(std::cos(o.yaw), -o.position.z / r, 1e-6);
  }
  // `speed` is the arc per frame.
  CameraPose a = cameraAt(Movement::Orbit, START, 0.5f, 1),
             b = cameraAt(Movement::Orbit, START, 0.5f, 0);
  EXPECT_NEAR(dist(a.position, b.position), 0.5, 1e-3);
}

TEST(Paths, MovementsMoveAsNamed) {
  Vec3d fwd{std::sin(START.yaw), 0.0, std::cos(START.yaw)};
  CameraPose f = cameraAt(Movement::Forward, START, 0.5f, 10);
  Vec3d df = f.position - START.position;
  EXPECT_NEAR(df.x * fwd.x + df.z * fwd.z, 5.0, 1e-6);
  CameraPose b = cameraAt(Movement::Backward, START, 0.5f, 10);
  Vec3d db = b.position - START.position;
  EXPECT_NEAR(db.x * fwd.x + db.z * fwd.z, -5.0, 1e-6);
  EXPECT_FLOAT_EQ(b.yaw, START.yaw);  // backward keeps looking forward
  CameraPose s = cameraAt(Movement::Sideways, START, 0.5f, 10);
  Vec3d ds = s.position - START.position;
  EXPECT_NEAR(ds.x * fwd.x + ds.z * fwd.z, 0.0, 1e-9);
  EXPECT_NEAR(dist(s.position, START.position), 5.0, 1e-6);
  CameraPose sp = cameraAt(Movement::Spinning, START, 0.5f, 10);
  EXPECT_NEAR(dist(sp.position, START.position), 0.0, 1e-12);
  EXPECT_GT(std::fabs(sp.yaw - START.yaw), 0.2f);
  CameraPose w = cameraAt(Movement::Walkthrough, START, 0.5f, 100);
  EXPECT_GT(dist(w.position, START.position), 30.0);
}

TEST(Paths, RejectsUnknownMovement) {
  EXPECT_THROW(parseMovement("moonwalk"), InputError);
}

// The prefetch's prediction: for a camera moving and turning at a constant rate, the frame it
// predicts after frames k and k + 1 is frame k + 2 (its eye across a change of local origin, its
// basis orthonormal and within a thousandth of a radian).
TEST(Paths, PredictNextFrameRepeatsTheLastStepAndTurn) {
  auto frameAt = [](int k) {
    CameraPose p{
        {1.0 + 3.1 * k, 2.0 + 0.2 * k, -5.0 - 2.3 * k}, 0.3f + 0.02f * k, -0.1f + 0.01f * k};
    return makeFrame(p, 0.01f, 320, 200, 8, k);
  };
  int originChanges = 0;
  for (int k = 0; k < 12; ++k) {
    FrameSetup a = frameAt(k), b = frameAt(k + 1), want = frameAt(k + 2);
    FrameSetup got = predictNextFrame(a, b);
    originChanges += dist(want.localOrigin, b.localOrigin) > 0.0;
    Vec3d gotEye = got.localOrigin + toDouble(got.eye),
          wantEye = want.localOrigin + toDouble(want.eye);
    EXPECT_LT(dist(gotEye, wantEye), 1e-4) << "frame " << k + 2;
    EXPECT_EQ(got.frameIndex, k + 2);
    const Vec3f g[3] = {got.basis.forward, got.basis.right, got.basis.up};
    const Vec3f w[3] = {want.basis.forward, want.basis.right, want.basis.up};
    for (int i = 0; i < 3; ++i) {
      EXPECT_GT(dot(g[i], w[i]), std::cos(1e-3f)) << "frame " << k + 2 << " axis " << i;
      EXPECT_NEAR(dot(g[i], g[i]), 1.0f, 1e-5f);
      EXPECT_NEAR(dot(g[i], g[(i + 1) % 3]), 0.0f, 1e-5f);
    }
  }
  EXPECT_GT(originChanges, 0) << "the path crosses a coarsest brick";
}

}  // namespace gvdp::detail
