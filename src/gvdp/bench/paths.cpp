#include "gvdp/bench/paths.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "gvdp/base/error.h"

namespace gvdp::detail {
namespace {
constexpr std::array<std::string_view, MOVEMENT_COUNT> NAMES = {
    "walkthrough", "forward", "backward", "sideways", "spinning", "orbit"};
Vec3d horizontal(float yaw) {
  return {std::sin(yaw), 0.0, std::cos(yaw)};
}
}  // namespace

std::string_view movementName(Movement m) {
  return NAMES[static_cast<int>(m)];
}

std::string movementNames() {
  std::string s;
  for (auto n : NAMES) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

Movement parseMovement(std::string_view name) {
  for (int i = 0; i < MOVEMENT_COUNT; ++i)
    if (NAMES[i] == name) return static_cast<Movement>(i);
  throw InputError("unknown movement '" + std::string(name) + "' (movements: " + movementNames() +
                   ")");
}

CameraPose cameraAt(Movement m, const CameraPose& start, float speed, int frame) {
  CameraPose pose = start;
  double f = frame, s = speed;
  Vec3d forward = horizontal(start.yaw);
  Vec3d right = {-forward.z, 0.0, forward.x};
  switch (m) {
    case Movement::Forward:
      pose.position = start.position + forward * (s * f);
      break;
    case Movement::Backward:
      pose.position = start.position - forward * (s * f);
      break;
    case Movement::Sideways:
      pose.position = start.position + right * (s * f);
      break;
    case Movement::Spinning:
      pose.yaw = start.yaw + static_cast<float>(f * 0.035);
      break;
    case Movement::Orbit: {
      // `speed` along the circle; the yaw looks at the axis (yaw 0 looks along +z).
      double radius = std::max(std::hypot(start.position.x, start.position.z), 1e-3);
      double angle = std::atan2(start.position.x, start.position.z) + s * f / radius;
      pose.position = {radius * std::sin(angle), start.position.y, radius * std::cos(angle)};
      pose.yaw = static_cast<float>(angle + PI);
      break;
    }
    case Movement::Walkthrough: {
      // The heading drifts smoothly (yaw0 + A sin(W f)) and the position sums the unit steps
      // along it; the eye rises and falls a little.
      const double A = 0.45, W = 0.021;
      Vec3d p = start.position;
      for (int i = 0; i < frame; ++i)
        p = p + horizontal(start.yaw + static_cast<float>(A * std::sin(W * i))) * s;
      pose.position = p;
      pose.position.y += 8.0 * s * std::sin(0.05 * f);
      pose.yaw = start.yaw + static_cast<float>(A * std::sin(W * f));
      pose.pitch = start.pitch + static_cast<float>(0.06 * std::sin(0.031 * f));
      break;
    }
  }
  return pose;
}

}  // namespace gvdp::detail
