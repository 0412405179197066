// Deterministic integer and "sin-hash" random numbers for the procedural producers. Integer
// hashes of lattice coordinates keep the worlds identical on CPU and GPU; the sin-hash is the
// paper's deliberately costly forest randomness (4.1).
#pragma once

#include <cstdint>

#include "gvdp/base/rounded_math.h"
#include "gvdp/base/vecmath.h"

namespace gvdp::detail {

GVDP_HD GVDP_INLINE uint32_t hashU32(uint32_t h) {
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return h;
}

GVDP_HD GVDP_INLINE uint32_t hash3(int x, int y, int z, uint32_t seed = 0) {
  uint32_t h = static_cast<uint32_t>(x) * 0x8da6b343u ^ static_cast<uint32_t>(y) * 0xd8163841u ^
               static_cast<uint32_t>(z) * 0xcb1ab31fu ^ seed * 0x9e3779b9u;
  return hashU32(h);
}

// Uniform float in [0, 1) from the top 24 bits.
GVDP_HD GVDP_INLINE float toUnit(uint32_t h) {
  return static_cast<float>(h >> 8) * (1.0f / 16777216.0f);
}

GVDP_HD GVDP_INLINE float hash3Unit(int x, int y, int z, uint32_t seed) {
  return toUnit(hash3(x, y, z, seed));
}

// The classic shader sin-hash, fract(sin(dot(p, k)) * 43758.5453), in [0, 1). The argument is
// computed without contraction (base/rounded_math.h) so that both backends take the sine of the
// same float: the hash amplifies any difference 43758 times.
GVDP_HD GVDP_INLINE float sinHash(float a, float b, float c, float k) {
  float arg = roundedMul(a, 12.9898f) + roundedMul(b, 78.233f) + roundedMul(c, 37.719f) +
              roundedMul(k, 4.581f);
  float s = roundedMul(sinf(arg), 43758.5453f);
  return s - floorf(s);
}

}  // namespace gvdp::detail
