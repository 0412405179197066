// The voxel: RGBA8, premultiplied colour and opacity, shading baked at production (paper 4.1).
// A producer returns a VoxelSample: the voxel and a conservative emptiness flag. A brick is
// EMPTY when all its 10^3 samples are flagged empty; producers guarantee that an empty flag at
// voxel size V implies zero opacity for every voxel of size <= V/2 whose centre is within V of
// that sample, so that skipping a coarse EMPTY brick equals sampling the finer levels.
#pragma once

#include <cstdint>

#include "gvdp/base/vecmath.h"

namespace gvdp::detail {

using Rgba8 = uint32_t;  // bytes r, g, b, a in memory order (little-endian), as uchar4

struct VoxelSample {
  Rgba8 rgba;
  bool empty;
};

// Opacity along a one-voxel step from a distance lower bound: a one-voxel-wide transition.
GVDP_HD GVDP_INLINE float coverage(float signedDistance, float voxelSize) {
  return clamp01(0.5f - signedDistance / voxelSize);
}

// The empty flag is raised when the distance to matter (a 1-Lipschitz lower bound) exceeds
// this many voxels; coverage() is nonzero only below 0.5 voxel, leaving room for sample spacing.
constexpr float EMPTY_MARGIN_VOXELS = 3.0f;

GVDP_HD GVDP_INLINE uint32_t toByte(float v) {
  return static_cast<uint32_t>(clamp01(v) * 255.0f + 0.5f);
}

GVDP_HD GVDP_INLINE Rgba8 packRgba8(Vec3f premultipliedColor, float alpha) {
  return toByte(premultipliedColor.x) | (toByte(premultipliedColor.y) << 8) |
         (toByte(premultipliedColor.z) << 16) | (toByte(alpha) << 24);
}

GVDP_HD GVDP_INLINE Vec4f unpackRgba8(Rgba8 v) {
  constexpr float S = 1.0f / 255.0f;
  return {static_cast<float>(v & 255u) * S, static_cast<float>((v >> 8) & 255u) * S,
          static_cast<float>((v >> 16) & 255u) * S, static_cast<float>(v >> 24) * S};
}

// Baked lighting: a sun and a sky-hemisphere ambient.
GVDP_HD GVDP_INLINE Vec3f bakeShading(Vec3f albedo, Vec3f normal) {
  const Vec3f SUN = {0.4364f, 0.8729f, 0.2182f};  // normalize(2, 4, 1)
  float diffuse = fmaxf(dot(normal, SUN), 0.0f);
  float ambient = 0.30f + 0.20f * normal.y;
  return albedo * (ambient + 0.85f * diffuse);
}

GVDP_HD GVDP_INLINE VoxelSample makeVoxel(Vec3f albedo, Vec3f normal, float alpha, bool empty) {
  if (alpha <= 0.0f) return {0u, empty};
  return {packRgba8(bakeShading(albedo, normal) * alpha, alpha), empty};
}

}  // namespace gvdp::detail
