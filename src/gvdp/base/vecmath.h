// Small vector types and helpers shared by host and device code. Plain aggregates (POD) so that
// they can be copied to the GPU as kernel arguments and stored in device buffers.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>

#include "gvdp/base/defs.h"

namespace gvdp::detail {

struct Vec3f {
  float x, y, z;
};
struct Vec3d {
  double x, y, z;
};
struct Vec3i {
  int x, y, z;
};
struct Vec4f {
  float x, y, z, w;
};

// --- Vec3f ---------------------------------------------------------------------------------
GVDP_HD GVDP_INLINE Vec3f operator+(Vec3f a, Vec3f b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
GVDP_HD GVDP_INLINE Vec3f operator-(Vec3f a, Vec3f b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
GVDP_HD GVDP_INLINE Vec3f operator-(Vec3f a) {
  return {-a.x, -a.y, -a.z};
}
GVDP_HD GVDP_INLINE Vec3f operator*(Vec3f a, float s) {
  return {a.x * s, a.y * s, a.z * s};
}
GVDP_HD GVDP_INLINE Vec3f operator*(float s, Vec3f a) {
  return a * s;
}
GVDP_HD GVDP_INLINE Vec3f operator*(Vec3f a, Vec3f b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
GVDP_HD GVDP_INLINE Vec3f operator/(Vec3f a, float s) {
  return a * (1.0f / s);
}
GVDP_HD GVDP_INLINE float dot(Vec3f a, Vec3f b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
GVDP_HD GVDP_INLINE Vec3f cross(Vec3f a, Vec3f b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
GVDP_HD GVDP_INLINE float length(Vec3f a) {
  return sqrtf(dot(a, a));
}
GVDP_HD GVDP_INLINE Vec3f normalize(Vec3f a) {
  float l = length(a);
  return l > 0.0f ? a / l : Vec3f{0.0f, 1.0f, 0.0f};
}
GVDP_HD GVDP_INLINE Vec3f abs(Vec3f a) {
  return {fabsf(a.x), fabsf(a.y), fabsf(a.z)};
}
GVDP_HD GVDP_INLINE float maxComponent(Vec3f a) {
  return fmaxf(a.x, fmaxf(a.y, a.z));
}
GVDP_HD GVDP_INLINE float minComponent(Vec3f a) {
  return fminf(a.x, fminf(a.y, a.z));
}

// --- Vec3d (world positions far from the origin) --------------------------------------------
GVDP_HD GVDP_INLINE Vec3d operator+(Vec3d a, Vec3d b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
GVDP_HD GVDP_INLINE Vec3d operator-(Vec3d a, Vec3d b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
GVDP_HD GVDP_INLINE Vec3d operator*(Vec3d a, double s) {
  return {a.x * s, a.y * s, a.z * s};
}
GVDP_HD GVDP_INLINE Vec3d toDouble(Vec3f a) {
  return {a.x, a.y, a.z};
}
GVDP_HD GVDP_INLINE Vec3f toFloat(Vec3d a) {
  return {static_cast<float>(a.x), static_cast<float>(a.y), static_cast<float>(a.z)};
}

// --- Vec3i ------------------------------------------------------------------------------------
GVDP_HD GVDP_INLINE Vec3i operator+(Vec3i a, Vec3i b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
GVDP_HD GVDP_INLINE Vec3i operator-(Vec3i a, Vec3i b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
GVDP_HD GVDP_INLINE bool operator==(Vec3i a, Vec3i b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}
GVDP_HD GVDP_INLINE Vec3i floorToInt(Vec3f a) {
  return {static_cast<int>(floorf(a.x)), static_cast<int>(floorf(a.y)),
          static_cast<int>(floorf(a.z))};
}
// Floor division for possibly negative integers (brick of a voxel, toroidal addressing).
GVDP_HD GVDP_INLINE int floorDiv(int a, int b) {
  int q = a / b;
  return (a % b != 0 && ((a < 0) != (b < 0))) ? q - 1 : q;
}
GVDP_HD GVDP_INLINE int floorMod(int a, int b) {
  return a - floorDiv(a, b) * b;
}
// The parent of a brick one level coarser: floor(a / 2) per axis (an arithmetic shift).
GVDP_HD GVDP_INLINE Vec3i halfFloor(Vec3i a) {
  return {a.x >> 1, a.y >> 1, a.z >> 1};
}
// 2^e as a float for e in [-126, 127]: ldexpf(1, e) without its range handling.
GVDP_HD GVDP_INLINE float exp2i(int e) {
#if GVDP_IS_GPU_CODE
  return __int_as_float((e + 127) << 23);
#else
  return std::bit_cast<float>(static_cast<uint32_t>(e + 127) << 23);
#endif
}

// --- scalars ------------------------------------------------------------------------------
GVDP_HD GVDP_INLINE float clamp01(float v) {
  return fminf(fmaxf(v, 0.0f), 1.0f);
}
GVDP_HD GVDP_INLINE float lerp(float a, float b, float t) {
  return a + (b - a) * t;
}
GVDP_HD GVDP_INLINE Vec3f lerp(Vec3f a, Vec3f b, float t) {
  return a + (b - a) * t;
}
GVDP_HD GVDP_INLINE float smoothstep(float e0, float e1, float x) {
  float t = clamp01((x - e0) / (e1 - e0));
  return t * t * (3.0f - 2.0f * t);
}

constexpr float PI = 3.14159265358979323846f;

}  // namespace gvdp::detail
