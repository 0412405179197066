// Everything a frame's rays need, as one POD passed by value to kernels: the local origin that
// keeps float positions small (a multiple of the coarsest brick, so that every level's bricks
// are aligned on it), the camera relative to it, the LOD and the timeline to record to.
#pragma once

#include "gvdp/base/camera.h"
#include "gvdp/base/ray.h"
#include "gvdp/profile/timeline.h"
#include "gvdp/render/lod.h"

namespace gvdp::detail {

struct FrameSetup {
  Vec3d localOrigin;  // world position of local (0, 0, 0)
  Vec3f eye;          // camera position relative to localOrigin
  CameraBasis basis;
  float tanHalfFov;  // horizontal
  int width, height;
  Lod lod;
  int frameIndex;
  TimelineView timeline;  // GPU-cores timeline of this frame (records null: off)

  GVDP_HD Ray primaryRay(int px, int py) const {
    float sx =
        (2.0f * (static_cast<float>(px) + 0.5f) / static_cast<float>(width) - 1.0f) * tanHalfFov;
    float sy = (1.0f - 2.0f * (static_cast<float>(py) + 0.5f) / static_cast<float>(height)) *
               tanHalfFov * static_cast<float>(height) / static_cast<float>(width);
    return {eye, normalize(basis.forward + basis.right * sx + basis.up * sy)};
  }
  GVDP_HD int pixelCount() const { return width * height; }
};

constexpr float DEFAULT_FOV_DEGREES = 60.0f;

inline FrameSetup makeFrame(const CameraPose& pose, float voxelSize0, int width, int height,
                            int levels, int frameIndex, float fovDegrees = DEFAULT_FOV_DEGREES) {
  FrameSetup f{};
  f.width = width;
  f.height = height;
  f.frameIndex = frameIndex;
  f.tanHalfFov = tanf(0.5f * fovDegrees * PI / 180.0f);
  f.lod = {voxelSize0, 2.0f * f.tanHalfFov / static_cast<float>(width), levels};
  double coarsestBrick = static_cast<double>(voxelSize0) * BRICK_WIDTH * (1 << (levels - 1));
  f.localOrigin = {floor(pose.position.x / coarsestBrick) * coarsestBrick,
                   floor(pose.position.y / coarsestBrick) * coarsestBrick,
                   floor(pose.position.z / coarsestBrick) * coarsestBrick};
  f.eye = toFloat(pose.position - f.localOrigin);
  f.basis = cameraBasis(pose);
  return f;
}

}  // namespace gvdp::detail
