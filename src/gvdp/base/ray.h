// Rays with a cone (paper 3.1: differential ray cones pick the LOD as MIP-mapping does).
// Origins are relative to the frame's local origin (render/frame.h), never world-absolute,
// so that precision does not degrade far from the world origin.
#pragma once

#include "gvdp/base/vecmath.h"

namespace gvdp::detail {

struct Ray {
  Vec3f o;  // relative to the frame's local origin
  Vec3f d;  // unit direction
};

// Distance along the ray at which it leaves the axis-aligned box [lo, hi] (slab method).
// The ray is assumed to be inside or in front of the box.
GVDP_HD GVDP_INLINE float boxExit(const Ray& r, Vec3f lo, Vec3f hi) {
  float tx = (r.d.x >= 0.0f ? hi.x - r.o.x : lo.x - r.o.x) / r.d.x;
  float ty = (r.d.y >= 0.0f ? hi.y - r.o.y : lo.y - r.o.y) / r.d.y;
  float tz = (r.d.z >= 0.0f ? hi.z - r.o.z : lo.z - r.o.z) / r.d.z;
  // A zero direction component gives +inf (or NaN for 0/0 on a face): fminf ignores NaN.
  return fminf(tx, fminf(ty, tz));
}

}  // namespace gvdp::detail
