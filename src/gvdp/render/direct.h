// The reference renderer's per-pixel body (docs/DESIGN.md "direct"): no cache; every sample
// evaluates the producer at the 8 voxel centres around it, quantises them to RGBA8 exactly as a
// brick would store them, and interpolates with the shared trilinear(). Every brick counts as
// resident, so the samples are those the cache would take, without its empty-space skipping
// (skipping is exact because producers are conservative).
#pragma once

#include "gvdp/render/frame.h"
#include "gvdp/render/march.h"
#include "gvdp/render/shade.h"
#include "gvdp/world/producer.h"

namespace gvdp::detail {

template <class P>
struct DirectAccess {
  const FrameSetup& frame;
  const P& producer;

  GVDP_HD BrickLookup lookup(int level, Vec3i brick) const {
    return {BrickState::Resident, 0u, level, brick};
  }
  GVDP_HD Vec4f sample(const BrickLookup& b, Vec3f p) const {
    double vs = frame.lod.voxelSize(b.level);
    Vec3f v = p / static_cast<float>(vs);
    Vec3d o = frame.localOrigin;
    float fvs = static_cast<float>(vs);
    return trilinear(v, [&](Vec3i i) {
      return [&, i](int dx, int dy, int dz) {
        int x = i.x + dx, y = i.y + dy, z = i.z + dz;
        Vec3d centre{o.x + (x + 0.5) * vs, o.y + (y + 0.5) * vs, o.z + (z + 0.5) * vs};
        return producer.voxel(centre, fvs).rgba;
      };
    });
  }
};

template <class P>
GVDP_HD GVDP_INLINE Rgba8 renderDirectPixel(const FrameSetup& frame, const P& producer, int pixel) {
  Ray ray = frame.primaryRay(pixel % frame.width, pixel / frame.width);
  RayState state = initialRayState();
  DirectAccess<P> access{frame, producer};
  march(ray, frame.lod, state, access);
  return resolvePixel(state.colour, ray.d);
}

}  // namespace gvdp::detail
