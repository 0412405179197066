#include "gvdp/serve/fly_camera.h"

#include <algorithm>
#include <cmath>

namespace gvdp::detail {

void FlyCamera::turn(float dyaw, float dpitch) {
  pose_.yaw = std::remainder(pose_.yaw + dyaw, 2.0f * static_cast<float>(M_PI));
  pose_.pitch = std::clamp(pose_.pitch + dpitch, -MAX_FLY_PITCH, MAX_FLY_PITCH);
}

void FlyCamera::fly(const Vec3f& direction, double speed, double seconds) {
  CameraBasis b = cameraBasis(pose_);
  double step = speed * seconds;
  auto axis = [&](const Vec3f& v, float amount) {
    pose_.position.x += static_cast<double>(v.x) * amount * step;
    pose_.position.y += static_cast<double>(v.y) * amount * step;
    pose_.position.z += static_cast<double>(v.z) * amount * step;
  };
  axis(b.right, direction.x);
  axis(Vec3f{0.0f, 1.0f, 0.0f}, direction.y);
  axis(b.forward, direction.z);
}

}  // namespace gvdp::detail
