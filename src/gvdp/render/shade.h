// The end of a ray: what is left of its transparency shows the sky; linear colour to 8-bit sRGB.
#pragma once

#include "gvdp/base/vecmath.h"
#include "gvdp/world/voxel.h"

namespace gvdp::detail {

GVDP_HD GVDP_INLINE Vec3f skyColour(Vec3f d) {
  if (d.y < 0.0f)
    return lerp(Vec3f{0.62f, 0.68f, 0.74f}, Vec3f{0.40f, 0.42f, 0.45f}, fminf(-d.y * 4.0f, 1.0f));
  return lerp(Vec3f{0.62f, 0.68f, 0.74f}, Vec3f{0.22f, 0.40f, 0.72f}, sqrtf(d.y));
}

GVDP_HD GVDP_INLINE float linearToSrgb(float v) {
  v = clamp01(v);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * powf(v, 1.0f / 2.4f) - 0.055f;
}

// Opaque RGBA8 pixel from a ray's accumulated premultiplied colour.
GVDP_HD GVDP_INLINE Rgba8 resolvePixel(Vec4f colour, Vec3f direction) {
  Vec3f sky = skyColour(direction);
  float k = 1.0f - colour.w;
  Vec3f c{colour.x + k * sky.x, colour.y + k * sky.y, colour.z + k * sky.z};
  return packRgba8({linearToSrgb(c.x), linearToSrgb(c.y), linearToSrgb(c.z)}, 1.0f);
}

}  // namespace gvdp::detail
