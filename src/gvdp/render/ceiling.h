// Lod::ceiling from a producer's box bound (world/producer.h), on the host, once per frame: per
// level, the lowest height from which the bound clears the level's whole clipmap window at the
// level's voxel size, plus the reach of the trilinear filter. Above it every sample of the level
// is zero, so a ray rising above the ceiling of every level it has left to cross ends there
// (render/march.h) and the image is the same: the sky costs no lookups. A world whose bound
// clears no such slab (random-spheres fills space) has none.
#pragma once

#include "gvdp/render/frame.h"
#include "gvdp/world/producer.h"

namespace gvdp::detail {

// How finely the bisection finds a level's cleared height, in voxels.
constexpr double CEILING_RESOLUTION = 1.0 / 16.0;

// Sets f.lod.ceiling for every level of f. A sample at p of a level of voxel size v reads the
// voxels whose centres lie within v of p along each axis (trilinear.h); the bound clears every
// centre of [x0, y, z0] - [x1, y1, z1] (a voxel flagged empty is zero: an EMPTY brick's own
// samples are skipped), and the window (clipmap.h: W bricks about the eye's brick, every sample
// of the level within it) lies inside that box with two bricks to spare: so every sample above
// y + v is zero. The ceiling adds a quarter voxel more, for the rounding of the march's float
// positions.
template <Producer P>
void setCeilings(FrameSetup& f, const P& producer) {
  Vec3d eye = f.localOrigin + toDouble(f.eye);
  double bricks = clipmapWidthFor(f.lod.pixelAngle) / 2 + 2;
  for (int level = 0; level < f.lod.levels; ++level) {
    float v = f.lod.voxelSize(level);
    double reach = bricks * BRICK_WIDTH * static_cast<double>(v);
    Vec3d hi{eye.x + reach, eye.y + reach, eye.z + reach};
    auto cleared = [&](double y) {
      return producer.emptyBox({eye.x - reach, y, eye.z - reach}, hi, v);
    };
    f.lod.ceiling[level] = NO_CEILING;
    double below = eye.y - reach, above = hi.y - v;  // cleared(above) once checked
    if (!cleared(above)) continue;
    if (cleared(below)) {
      above = below;
    } else {
      while (above - below > CEILING_RESOLUTION * v) {
        double middle = 0.5 * (below + above);
        (cleared(middle) ? above : below) = middle;
      }
    }
    f.lod.ceiling[level] = static_cast<float>(above - f.localOrigin.y + 1.25 * v);
  }
}

}  // namespace gvdp::detail
