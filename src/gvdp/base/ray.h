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

// The reciprocal of a ray's direction, once per ray: planesExit multiplies by it (a zero
// component gives an infinity of its sign, as the division would).
GVDP_HD GVDP_INLINE Vec3f inverseDirection(const Ray& r) {
  return {1.0f / r.d.x, 1.0f / r.d.y, 1.0f / r.d.z};
}

// Distance along the ray at which it meets the first of three axis-aligned planes ahead of it
// (x = exit.x, y = exit.y, z = exit.z), with invD = inverseDirection(r).
GVDP_HD GVDP_INLINE float planesExit(const Ray& r, Vec3f invD, Vec3f exit) {
  float tx = (exit.x - r.o.x) * invD.x;
  float ty = (exit.y - r.o.y) * invD.y;
  float tz = (exit.z - r.o.z) * invD.z;
  // A zero direction component gives +inf (or NaN for 0 * inf on a face): fminf ignores NaN.
  return fminf(tx, fminf(ty, tz));
}

}  // namespace gvdp::detail
