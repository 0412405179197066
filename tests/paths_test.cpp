#include <gtest/gtest.h>

#include "gvdp/base/error.h"
#include "gvdp/bench/paths.h"

namespace gvdp {

namespace {
const CameraPose START{{10.0, 5.0, -3.0}, 0.4f, -0.1f};
double dist(Vec3d a, Vec3d b) {
  Vec3d d = a - b;
  return std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
}
}  // namespace

TEST(Paths, EveryMovementStartsAtTheStartAndIsDeterministic) {
  for (int m = 0; m < MOVEMENT_COUNT; ++m) {
    Movement mv = static_cast<Movement>(m);
    CameraPose p0 = cameraAt(mv, START, 0.5f, 0);
    EXPECT_NEAR(dist(p0.position, START.position), 0.0, 1e-12) << movementName(mv);
    EXPECT_FLOAT_EQ(p0.yaw, START.yaw);
    CameraPose a = cameraAt(mv, START, 0.5f, 37), b = cameraAt(mv, START, 0.5f, 37);
    EXPECT_EQ(a.position.x, b.position.x);
    EXPECT_EQ(a.yaw, b.yaw);
    EXPECT_EQ(parseMovement(movementName(mv)), mv);
  }
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

}  // namespace gvdp
