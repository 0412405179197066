// 3D gradient noise (Perlin's improved noise, hashed lattice gradients, quintic fade) with its
// analytic gradient, for producers that bake shading from the density gradient (docs/DESIGN.md).
// Lattice reduction happens in double precision so that a world a million units from the
// origin is as detailed as at the origin; the rest is float.
#pragma once

#include "gvdp/base/vecmath.h"
#include "gvdp/world/hash.h"

namespace gvdp::detail {

// Bounds used by producers to stay conservative (tests/world_test.cpp checks them on random
// points): |noise| <= NOISE_MAX_ABS, |grad noise| <= NOISE_LIPSCHITZ per lattice unit, and the
// Hessian's norm <= NOISE_HESSIAN per lattice unit squared (its Frobenius norm, an upper bound of
// the spectral one, reaches 16.17 at most: a search over the 16^8 gradient choices of a cell and
// the position in it, by random restarts and hill climbing, converges there; the quintic fade
// keeps the Hessian continuous across cells).
constexpr float NOISE_MAX_ABS = 1.05f;
constexpr float NOISE_LIPSCHITZ = 3.5f;
constexpr float NOISE_HESSIAN = 17.0f;

struct NoiseSample {
  float value;
  Vec3f grad;  // per lattice unit
};

// One of the 12 cube-edge directions of improved noise (4 of them twice, to make 16), from the
// hash bits by arithmetic. (A switch returning vector literals would compile, under relocatable
// device code, to per-file constant tables that the device linker merges by name: wrong vectors.)
GVDP_HD GVDP_INLINE Vec3f latticeGradient(int x, int y, int z, uint32_t seed) {
  uint32_t h = hash3(x, y, z, seed) & 15u;
  int u = h < 8u ? 0 : 1;                               // first axis: x or y
  int v = h < 4u ? 1 : (h == 12u || h == 14u ? 0 : 2);  // second axis
  float su = (h & 1u) ? -1.0f : 1.0f, sv = (h & 2u) ? -1.0f : 1.0f;
  return {(u == 0 ? su : 0.0f) + (v == 0 ? sv : 0.0f), (u == 1 ? su : 0.0f) + (v == 1 ? sv : 0.0f),
          v == 2 ? sv : 0.0f};
}

// gradientNoise's linkage: inlined at every call, except in the device code of a translation unit
// that defines GVDP_NOISE_OUT_OF_LINE (pt's workers of perlin and fbm,
// sched/pt_noise_workers.cpp), where one copy of its own serves all of its call sites.
#if defined(__CUDA_ARCH__) && defined(GVDP_NOISE_OUT_OF_LINE)
#define GVDP_NOISE_LINKAGE static __noinline__
#else
#define GVDP_NOISE_LINKAGE GVDP_INLINE
#endif

// Noise at p (lattice units, double) with its gradient. Value roughly in [-1, 1].
GVDP_HD GVDP_NOISE_LINKAGE NoiseSample gradientNoise(Vec3d p, uint32_t seed) {
  double fx = floor(p.x), fy = floor(p.y), fz = floor(p.z);
  // Lattice coordinates wrap modulo 2^32 through int64: the hash only needs them distinct locally.
  int ix = static_cast<int>(static_cast<long long>(fx));
  int iy = static_cast<int>(static_cast<long long>(fy));
  int iz = static_cast<int>(static_cast<long long>(fz));
  Vec3f w{static_cast<float>(p.x - fx), static_cast<float>(p.y - fy), static_cast<float>(p.z - fz)};
  Vec3f u{w.x * w.x * w.x * (w.x * (w.x * 6.0f - 15.0f) + 10.0f),
          w.y * w.y * w.y * (w.y * (w.y * 6.0f - 15.0f) + 10.0f),
          w.z * w.z * w.z * (w.z * (w.z * 6.0f - 15.0f) + 10.0f)};
  Vec3f du{30.0f * w.x * w.x * (w.x * (w.x - 2.0f) + 1.0f),
           30.0f * w.y * w.y * (w.y * (w.y - 2.0f) + 1.0f),
           30.0f * w.z * w.z * (w.z * (w.z - 2.0f) + 1.0f)};

  Vec3f ga = latticeGradient(ix, iy, iz, seed), gb = latticeGradient(ix + 1, iy, iz, seed);
  Vec3f gc = latticeGradient(ix, iy + 1, iz, seed), gd = latticeGradient(ix + 1, iy + 1, iz, seed);
  Vec3f ge = latticeGradient(ix, iy, iz + 1, seed), gf = latticeGradient(ix + 1, iy, iz + 1, seed);
  Vec3f gg = latticeGradient(ix, iy + 1, iz + 1, seed);
  Vec3f gh = latticeGradient(ix + 1, iy + 1, iz + 1, seed);

  float va = dot(ga, w);
  float vb = dot(gb, w - Vec3f{1, 0, 0});
  float vc = dot(gc, w - Vec3f{0, 1, 0});
  float vd = dot(gd, w - Vec3f{1, 1, 0});
  float ve = dot(ge, w - Vec3f{0, 0, 1});
  float vf = dot(gf, w - Vec3f{1, 0, 1});
  float vg = dot(gg, w - Vec3f{0, 1, 1});
  float vh = dot(gh, w - Vec3f{1, 1, 1});

  float k1 = vb - va, k2 = vc - va, k3 = ve - va;
  float k4 = va - vb - vc + vd, k5 = va - vc - ve + vg, k6 = va - vb - ve + vf;
  float k7 = -va + vb + vc - vd + ve - vf - vg + vh;

  NoiseSample s;
  s.value = va + u.x * k1 + u.y * k2 + u.z * k3 + u.x * u.y * k4 + u.y * u.z * k5 + u.z * u.x * k6 +
            u.x * u.y * u.z * k7;
  Vec3f g = ga + (gb - ga) * u.x + (gc - ga) * u.y + (ge - ga) * u.z +
            (ga - gb - gc + gd) * (u.x * u.y) + (ga - gc - ge + gg) * (u.y * u.z) +
            (ga - gb - ge + gf) * (u.z * u.x) +
            (-ga + gb + gc - gd + ge - gf - gg + gh) * (u.x * u.y * u.z);
  g.x += du.x * (k1 + u.y * k4 + u.z * k6 + u.y * u.z * k7);
  g.y += du.y * (k2 + u.z * k5 + u.x * k4 + u.z * u.x * k7);
  g.z += du.z * (k3 + u.x * k6 + u.y * k5 + u.x * u.y * k7);
  s.grad = g;
  return s;
}
#undef GVDP_NOISE_LINKAGE

}  // namespace gvdp::detail
