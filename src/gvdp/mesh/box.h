// Axis-aligned boxes and the float arithmetic the kd-tree's rules are written in.
// Every operation the SAH, the event order and the traversal depend on is a correctly rounded
// IEEE single-precision operation written out one at a time (base/rounded_math.h: roundedMul,
// roundedAdd, roundedSub, roundedDiv), and the mesh sources are compiled with -ffp-contract=off
// (src/CMakeLists.txt). A CPU and a GPU builder therefore compute the same bits for the same
// inputs, so they pick the same splits.
#pragma once

#include <cstdint>

#include "gvdp/base/defs.h"
#include "gvdp/base/rounded_math.h"
#include "gvdp/base/vecmath.h"

namespace gvdp::detail {

// Component `axis` (0 x, 1 y, 2 z) of a vector.
GVDP_HD GVDP_INLINE float component(Vec3f v, int axis) {
  return axis == 0 ? v.x : (axis == 1 ? v.y : v.z);
}
GVDP_HD GVDP_INLINE void setComponent(Vec3f& v, int axis, float value) {
  if (axis == 0)
    v.x = value;
  else if (axis == 1)
    v.y = value;
  else
    v.z = value;
}

// A closed box [lo, hi]; empty when lo > hi on some axis.
struct Box3f {
  Vec3f lo, hi;
};

GVDP_HD GVDP_INLINE Box3f emptyBox() {
  constexpr float BIG = 3.402823466e38f;
  return {{BIG, BIG, BIG}, {-BIG, -BIG, -BIG}};
}
GVDP_HD GVDP_INLINE Box3f merge(Box3f b, Vec3f p) {
  return {{fminf(b.lo.x, p.x), fminf(b.lo.y, p.y), fminf(b.lo.z, p.z)},
          {fmaxf(b.hi.x, p.x), fmaxf(b.hi.y, p.y), fmaxf(b.hi.z, p.z)}};
}
GVDP_HD GVDP_INLINE Box3f merge(Box3f a, Box3f b) {
  return merge(merge(a, b.lo), b.hi);
}
GVDP_HD GVDP_INLINE Box3f triangleBox(Vec3f a, Vec3f b, Vec3f c) {
  return merge(merge(merge(emptyBox(), a), b), c);
}
// Whether two closed boxes share a point.
GVDP_HD GVDP_INLINE bool boxesMeet(Box3f a, Box3f b) {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y &&
         a.lo.z <= b.hi.z && b.lo.z <= a.hi.z;
}

// Half the surface area (the SAH needs only ratios): dx dy + dy dz + dz dx, in that order.
GVDP_HD GVDP_INLINE float halfArea(Box3f b) {
  float dx = roundedSub(b.hi.x, b.lo.x), dy = roundedSub(b.hi.y, b.lo.y),
        dz = roundedSub(b.hi.z, b.lo.z);
  return roundedAdd(roundedAdd(roundedMul(dx, dy), roundedMul(dy, dz)), roundedMul(dz, dx));
}

// -0 becomes +0, so that equal positions have equal bits (event keys, tie-breaks).
GVDP_HD GVDP_INLINE float canonicalZero(float x) {
  return x == 0.0f ? 0.0f : x;
}

}  // namespace gvdp::detail
