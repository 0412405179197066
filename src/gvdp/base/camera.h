// Pinhole camera with a horizontal field of view; poses are world-absolute (double) and every
// frame re-expresses them relative to a local origin (render/frame.h).
#pragma once

#include "gvdp/base/vecmath.h"

namespace gvdp::detail {

struct CameraPose {
  Vec3d position;
  float yaw;    // radians, 0 looks along +z, positive turns towards +x
  float pitch;  // radians, positive looks up
};

struct CameraBasis {
  Vec3f forward, right, up;
};

inline CameraBasis cameraBasis(const CameraPose& pose) {
  float cp = cosf(pose.pitch), sp = sinf(pose.pitch);
  float cy = cosf(pose.yaw), sy = sinf(pose.yaw);
  CameraBasis b;
  b.forward = {sy * cp, sp, cy * cp};
  b.right = {-cy, 0.0f, sy};  // forward x world-up, normalised
  b.up = cross(b.right, b.forward);
  return b;
}

}  // namespace gvdp::detail
