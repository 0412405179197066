// Trilinear interpolation of RGBA8 voxels stored at voxel centres. Both the direct renderer
// (which evaluates the producer at the 8 centres) and the CPU brick pool call this one function
// with their own fetch, so that on the CPU backend they agree bit for bit.
#pragma once

#include "gvdp/base/vecmath.h"
#include "gvdp/world/voxel.h"

namespace gvdp::detail {

GVDP_HD GVDP_INLINE Vec4f lerp4(Vec4f a, Vec4f b, float t) {
  return {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t, a.z + (b.z - a.z) * t,
          a.w + (b.w - a.w) * t};
}

// Where trilinear() reads for a position v in voxel units of one level: the 2x2x2 block of voxels
// from `first` on (the voxels whose centres, at i + 1/2, surround v) and the weights per axis.
struct TrilinearSite {
  Vec3i first;
  Vec3f f;
};

GVDP_HD GVDP_INLINE TrilinearSite trilinearSite(Vec3f v) {
  Vec3f u{v.x - 0.5f, v.y - 0.5f, v.z - 0.5f};
  Vec3i i = floorToInt(u);
  return {i,
          {u.x - static_cast<float>(i.x), u.y - static_cast<float>(i.y),
           u.z - static_cast<float>(i.z)}};
}

// The interpolation at a site; at(dx, dy, dz) (each 0 or 1) gives voxel first + d. Returns
// premultiplied RGBA in [0, 1].
template <class At>
GVDP_HD GVDP_INLINE Vec4f interpolate(const TrilinearSite& s, At&& at) {
  Vec4f c00 = lerp4(unpackRgba8(at(0, 0, 0)), unpackRgba8(at(1, 0, 0)), s.f.x);
  Vec4f c10 = lerp4(unpackRgba8(at(0, 1, 0)), unpackRgba8(at(1, 1, 0)), s.f.x);
  Vec4f c01 = lerp4(unpackRgba8(at(0, 0, 1)), unpackRgba8(at(1, 0, 1)), s.f.x);
  Vec4f c11 = lerp4(unpackRgba8(at(0, 1, 1)), unpackRgba8(at(1, 1, 1)), s.f.x);
  return lerp4(lerp4(c00, c10, s.f.y), lerp4(c01, c11, s.f.y), s.f.z);
}

// v: position in voxel units; block(i) returns the 2x2x2 voxels from voxel i on, as a callable
// at(dx, dy, dz). The block is asked for once, so that a pool computes one address and reads the
// eight voxels at constant offsets from it (BrickPool::sample).
template <class Block>
GVDP_HD GVDP_INLINE Vec4f trilinear(Vec3f v, Block&& block) {
  TrilinearSite s = trilinearSite(v);
  return interpolate(s, block(s.first));
}

}  // namespace gvdp::detail
