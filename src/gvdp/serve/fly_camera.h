// The viewer's camera: flown by held keys (a direction in the camera's frame, at a speed in world
// units per second, integrated over the wall-clock time between frames) and turned by mouse drags.
#pragma once

#include "gvdp/base/camera.h"

namespace gvdp::detail {

// Pitch stops short of straight up or down, where yaw would lose its meaning.
constexpr float MAX_FLY_PITCH = 1.5f;  // radians, about 86 degrees

class FlyCamera {
 public:
  explicit FlyCamera(const CameraPose& start) : pose_(start) {}
  // Turns by (dyaw, dpitch) radians; pitch is clamped to +-MAX_FLY_PITCH.
  void turn(float dyaw, float dpitch);
  // Moves along (right, up, forward) in the camera's frame (forward follows the pitch, up is the
  // world's), each component in -1..1, at `speed` units per second for `seconds`.
  void fly(const Vec3f& direction, double speed, double seconds);
  const CameraPose& pose() const { return pose_; }

 private:
  CameraPose pose_;
};

}  // namespace gvdp::detail
