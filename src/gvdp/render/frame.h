// Everything a frame's rays need, as one POD passed by value to kernels: the local origin that
// keeps float positions small (a multiple of the coarsest brick, so that every level's bricks
// are aligned on it), the camera relative to it, the LOD and the timeline to record to. A frame
// may be a tile of a larger image (tiles/tiled_frame.h): its width x height pixels are the
// image's from (tileX, tileY), and its rays are the image's, bit for bit.
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
  float tanHalfFov;             // horizontal
  int width, height;            // the pixels this frame renders (a tile's, or the image's)
  int tileX, tileY;             // where they lie in the image
  int imageWidth, imageHeight;  // the image the camera projects onto
  Lod lod;
  int frameIndex;
  bool coldCache;         // start from an empty cache (a degraded frame's retry: tiled_frame.h)
  TimelineView timeline;  // GPU-cores timeline of this frame (records null: off)
  bool rayCosts;          // record each pixel's lookups, samples, stops (FrameStats::rayCosts)

  // The ray of pixel (px, py) of this frame: pixel (tileX + px, tileY + py) of the image.
  GVDP_HD Ray primaryRay(int px, int py) const {
    float ix = static_cast<float>(px + tileX), iy = static_cast<float>(py + tileY);
    float w = static_cast<float>(imageWidth), h = static_cast<float>(imageHeight);
    float sx = (2.0f * (ix + 0.5f) / w - 1.0f) * tanHalfFov;
    float sy = (1.0f - 2.0f * (iy + 0.5f) / h) * tanHalfFov * h / w;
    return {eye, normalize(basis.forward + basis.right * sx + basis.up * sy)};
  }
  GVDP_HD int pixelCount() const { return width * height; }
};

// Whether two frames see from the same place in the same direction.
inline bool sameView(const FrameSetup& a, const FrameSetup& b) {
  auto same = [](auto p, auto q) { return p.x == q.x && p.y == q.y && p.z == q.z; };
  return same(a.localOrigin, b.localOrigin) && same(a.eye, b.eye) &&
         same(a.basis.forward, b.basis.forward) && same(a.basis.right, b.basis.right) &&
         same(a.basis.up, b.basis.up);
}

// The frame after `current` as the camera's motion from `previous` predicts it: the same step
// and turn again (the basis extrapolated and made orthonormal), in `current`'s local coordinates,
// size and LOD. What pt's idle-time prefetch marches.
inline FrameSetup predictNextFrame(const FrameSetup& previous, const FrameSetup& current) {
  FrameSetup next = current;
  Vec3d step =
      current.localOrigin - previous.localOrigin + toDouble(current.eye) - toDouble(previous.eye);
  next.eye = toFloat(toDouble(current.eye) + step);
  const CameraBasis &a = previous.basis, &b = current.basis;
  Vec3f f = normalize(b.forward * 2.0f - a.forward);
  Vec3f r = b.right * 2.0f - a.right;
  r = normalize(r - f * dot(r, f));
  Vec3f u = b.up * 2.0f - a.up;
  next.basis = {f, r, normalize(u - f * dot(u, f) - r * dot(u, r))};
  next.frameIndex = current.frameIndex + 1;
  return next;
}

// The frame of pixels [x, x + w) x [y, y + h) of `image` (a frame of the whole image).
inline FrameSetup tileOf(const FrameSetup& image, int x, int y, int w, int h) {
  FrameSetup t = image;
  t.tileX = image.tileX + x;
  t.tileY = image.tileY + y;
  t.width = w;
  t.height = h;
  return t;
}

constexpr float DEFAULT_FOV_DEGREES = 60.0f;

// The widest image whose pixel footprint picks the levels by default: the clipmap's windows grow
// as the cube of it (clipmapWidthFor: 328 entries a side at 1500 pixels, 0.28 GB of entries for 8
// levels; 22.6 GB at 4096, measured), so a wider image samples the levels of this width (several
// rays per voxel).
constexpr int MAX_LOD_WIDTH = 4096;

// lodWidth: the image width whose pixel footprint picks the levels (0: `width`, up to
// MAX_LOD_WIDTH).
inline FrameSetup makeFrame(const CameraPose& pose, float voxelSize0, int width, int height,
                            int levels, int frameIndex, float fovDegrees = DEFAULT_FOV_DEGREES,
                            int lodWidth = 0) {
  FrameSetup f{};
  f.width = f.imageWidth = width;
  f.height = f.imageHeight = height;
  f.frameIndex = frameIndex;
  f.tanHalfFov = tanf(0.5f * fovDegrees * PI / 180.0f);
  if (lodWidth <= 0) lodWidth = width < MAX_LOD_WIDTH ? width : MAX_LOD_WIDTH;
  f.lod = {voxelSize0, 2.0f * f.tanHalfFov / static_cast<float>(lodWidth), levels};
  double coarsestBrick = static_cast<double>(voxelSize0) * BRICK_WIDTH * (1 << (levels - 1));
  f.localOrigin = {floor(pose.position.x / coarsestBrick) * coarsestBrick,
                   floor(pose.position.y / coarsestBrick) * coarsestBrick,
                   floor(pose.position.z / coarsestBrick) * coarsestBrick};
  f.eye = toFloat(pose.position - f.localOrigin);
  f.basis = cameraBasis(pose);
  return f;
}

}  // namespace gvdp::detail
