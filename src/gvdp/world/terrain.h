// The two noise scenes of the paper (4.1): `perlin`, a density made of two 3D gradient-noise
// layers over a height gradient (cliffs, arches, caves), and `fbm`, up to ten octaves whose count
// follows the voxel size (fractal depth adapted to the LOD). Matter where density > 0.
//
// Conservativeness: with Lip a Lipschitz bound of the density d, -d/Lip is a lower bound of the
// distance to matter; coverage uses -d/|grad d| (sharper) which is nonzero only where
// -d/Lip < 0.5 voxel. For fbm the octaves a finer level adds are bounded by their amplitudes.
#pragma once

#include "gvdp/world/noise.h"
#include "gvdp/world/voxel.h"

namespace gvdp::detail {

struct DensitySample {
  float d;
  Vec3f grad;
};

GVDP_HD GVDP_INLINE Vec3d scaled(Vec3d p, double s) {
  return {p.x * s, p.y * s, p.z * s};
}

// Shared shading of density fields: coverage from the gradient-estimated distance.
GVDP_HD GVDP_INLINE float densityCoverage(const DensitySample& s, float voxelSize) {
  return coverage(-s.d / fmaxf(length(s.grad), 1e-6f), voxelSize);
}

// --- perlin ---------------------------------------------------------------------------------
constexpr float PERLIN_HEIGHT = 24.0f;
constexpr float PERLIN_WAVE0 = 32.0f, PERLIN_WAVE1 = 9.0f, PERLIN_AMP1 = 0.4f;
constexpr float PERLIN_LIPSCHITZ = 1.0f / PERLIN_HEIGHT + NOISE_LIPSCHITZ / PERLIN_WAVE0 +
                                   PERLIN_AMP1 * NOISE_LIPSCHITZ / PERLIN_WAVE1;
// The height gradient is linear: only the noise layers bend the density.
constexpr float PERLIN_BASE_LIPSCHITZ = 1.0f / PERLIN_HEIGHT + NOISE_LIPSCHITZ / PERLIN_WAVE0;
constexpr float PERLIN_BASE_HESSIAN = NOISE_HESSIAN / (PERLIN_WAVE0 * PERLIN_WAVE0);
constexpr float PERLIN_HESSIAN =
    PERLIN_BASE_HESSIAN + PERLIN_AMP1 * NOISE_HESSIAN / (PERLIN_WAVE1 * PERLIN_WAVE1);

// perlin's density in two parts: the height term with the first noise layer (base), and the
// second layer (detail).
struct PerlinLayers {
  DensitySample base, detail;
};

GVDP_HD GVDP_INLINE PerlinLayers perlinLayers(Vec3d p, uint32_t seed) {
  NoiseSample n0 = gradientNoise(scaled(p, 1.0 / PERLIN_WAVE0), seed);
  NoiseSample n1 = gradientNoise(scaled(p, 1.0 / PERLIN_WAVE1), seed + 1);
  float y = static_cast<float>(p.y);
  return {{-y / PERLIN_HEIGHT + n0.value,
           Vec3f{0.0f, -1.0f / PERLIN_HEIGHT, 0.0f} + n0.grad * (1.0f / PERLIN_WAVE0)},
          {PERLIN_AMP1 * n1.value, n1.grad * (PERLIN_AMP1 / PERLIN_WAVE1)}};
}

GVDP_HD GVDP_INLINE DensitySample perlinDensity(Vec3d p, uint32_t seed) {
  PerlinLayers l = perlinLayers(p, seed);
  return {l.base.d + l.detail.d, l.base.grad + l.detail.grad};
}

GVDP_HD GVDP_INLINE Vec3f rockAlbedo(float y, Vec3f normal) {
  float strata = 0.5f + 0.5f * sinf(y * 0.9f + 0.3f * sinf(y * 0.13f));
  Vec3f rock = lerp(Vec3f{0.42f, 0.33f, 0.25f}, Vec3f{0.62f, 0.52f, 0.40f}, strata);
  Vec3f grass{0.27f, 0.45f, 0.17f};
  return lerp(rock, grass, smoothstep(0.65f, 0.85f, normal.y));
}

GVDP_HD GVDP_INLINE VoxelSample producePerlin(Vec3d p, float voxelSize, uint32_t seed) {
  DensitySample s = perlinDensity(p, seed);
  bool empty = -s.d / PERLIN_LIPSCHITZ >= EMPTY_MARGIN_VOXELS * voxelSize;
  float alpha = densityCoverage(s, voxelSize);
  Vec3f normal = normalize(-s.grad);
  return makeVoxel(rockAlbedo(static_cast<float>(p.y), normal), normal, alpha, empty);
}

// Box bounds (the producer's emptyBox, world/producer.h): every point of the box lies within r,
// half its diagonal, of the centre c, so the density there is at most
//   d(c) + min(Lip r, |grad d(c)| r + H r^2 / 2)
// with Lip a bound of the gradient's norm and H of the Hessian's (Taylor's theorem with the
// remainder at some point of the segment). The second form is the sharper one near the camera,
// where boxes are a few bricks wide and the gradient is a third of its bound or less: perlin's
// rays at 750x500 crossed 70% of their EMPTY bricks one by one under the first alone.
// DENSITY_SLACK covers the float rounding of the density at the voxel centres, whose empty flags
// the bound must imply.
constexpr float DENSITY_SLACK = 1e-3f;

struct BoxCentre {
  Vec3d centre;
  float halfDiagonal;
};

GVDP_HD GVDP_INLINE BoxCentre boxCentre(Vec3d lo, Vec3d hi) {
  double dx = hi.x - lo.x, dy = hi.y - lo.y, dz = hi.z - lo.z;
  return {{0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y), 0.5 * (lo.z + hi.z)},
          static_cast<float>(0.5 * sqrt(dx * dx + dy * dy + dz * dz))};
}

// The largest density within r of the sample's point (see above).
GVDP_HD GVDP_INLINE float densityBoundWithin(const DensitySample& s, float r, float lipschitz,
                                             float hessian) {
  return s.d + fminf(lipschitz * r, (length(s.grad) + 0.5f * hessian * r) * r);
}

// producePerlin flags a voxel empty when -d >= 3 v Lip. Three upper bounds of d over the box, the
// smallest kept: the centre's (densityBoundWithin; tight near the surface), the same for the
// height and first layer with the second layer's amplitude added, and the height one, d <=
// -y / H plus the noise layers' largest values (above the terrain, where the first is loose at
// coarse levels: one lookup then skips a sky ray over a whole level).
GVDP_HD GVDP_INLINE bool perlinEmptyBox(Vec3d lo, Vec3d hi, float voxelSize, uint32_t seed) {
  BoxCentre b = boxCentre(lo, hi);
  float dHeight = -static_cast<float>(lo.y) / PERLIN_HEIGHT + (1.0f + PERLIN_AMP1) * NOISE_MAX_ABS;
  PerlinLayers l = perlinLayers(b.centre, seed);
  DensitySample whole{l.base.d + l.detail.d, l.base.grad + l.detail.grad};
  float dWhole = densityBoundWithin(whole, b.halfDiagonal, PERLIN_LIPSCHITZ, PERLIN_HESSIAN);
  // In a box wider than the second layer's wavelength, its amplitude bounds it better.
  float dBase =
      densityBoundWithin(l.base, b.halfDiagonal, PERLIN_BASE_LIPSCHITZ, PERLIN_BASE_HESSIAN) +
      PERLIN_AMP1 * NOISE_MAX_ABS;
  float dMax = fminf(fminf(dWhole, dBase), dHeight);
  return -dMax >= PERLIN_LIPSCHITZ * EMPTY_MARGIN_VOXELS * voxelSize + DENSITY_SLACK;
}

// --- fbm --------------------------------------------------------------------------------------
constexpr int FBM_MAX_OCTAVES = 10;
constexpr float FBM_HEIGHT = 48.0f, FBM_WAVE0 = 128.0f;

// Octave o (wavelength FBM_WAVE0 / 2^o) is used while it spans at least 4 voxels.
GVDP_HD GVDP_INLINE int fbmOctaves(float voxelSize) {
  int n = 1;
  while (n < FBM_MAX_OCTAVES && FBM_WAVE0 / static_cast<float>(1 << n) >= 4.0f * voxelSize) ++n;
  return n;
}
// Each octave adds amplitude 2^-o and slope 2^-o * 2^o / WAVE0: the same Lipschitz term; its
// curvature is 2^-o * (2^o / WAVE0)^2 = 2^o / WAVE0^2 times the noise's.
GVDP_HD GVDP_INLINE float fbmLipschitz(int octaves) {
  return 1.0f / FBM_HEIGHT + static_cast<float>(octaves) * NOISE_LIPSCHITZ / FBM_WAVE0;
}
GVDP_HD GVDP_INLINE float fbmHessian(int octaves) {
  return static_cast<float>((1 << octaves) - 1) * NOISE_HESSIAN / (FBM_WAVE0 * FBM_WAVE0);
}
GVDP_HD GVDP_INLINE float fbmRemainder(int octaves) {
  float r = 0.0f;
  for (int o = octaves; o < FBM_MAX_OCTAVES; ++o) r += NOISE_MAX_ABS / static_cast<float>(1 << o);
  return r;
}

GVDP_HD GVDP_INLINE DensitySample fbmDensity(Vec3d p, int octaves, uint32_t seed) {
  DensitySample s{-static_cast<float>(p.y) / FBM_HEIGHT, {0.0f, -1.0f / FBM_HEIGHT, 0.0f}};
  double freq = 1.0 / FBM_WAVE0;
  float amp = 1.0f;
  for (int o = 0; o < octaves; ++o) {
    NoiseSample n = gradientNoise(scaled(p, freq), seed + static_cast<uint32_t>(o));
    s.d += amp * n.value;
    s.grad = s.grad + n.grad * (amp * static_cast<float>(freq));
    freq *= 2.0;
    amp *= 0.5f;
  }
  return s;
}

// A voxel of this size is empty only if no finer level (more octaves, smaller voxels) can put
// matter within one coarse voxel of it: slope over that distance + the octaves still to come +
// the finest coverage band (max over v <= V/2 of 0.5 v Lip(v), reached at v = V/2). Empty when
// d <= -1.5 reach.
GVDP_HD GVDP_INLINE float fbmEmptyReach(float voxelSize, int octaves) {
  return fbmLipschitz(octaves) * voxelSize + fbmRemainder(octaves) +
         0.25f * voxelSize * fbmLipschitz(fbmOctaves(0.5f * voxelSize));
}

GVDP_HD GVDP_INLINE VoxelSample produceFbm(Vec3d p, float voxelSize, uint32_t seed) {
  int octaves = fbmOctaves(voxelSize);
  DensitySample s = fbmDensity(p, octaves, seed);
  bool empty = s.d <= -1.5f * fbmEmptyReach(voxelSize, octaves);
  float alpha = densityCoverage(s, voxelSize);
  Vec3f normal = normalize(-s.grad);
  float y = static_cast<float>(p.y);
  Vec3f albedo = rockAlbedo(y, normal);
  float snow = smoothstep(28.0f, 40.0f, y + 8.0f * normal.y);
  albedo = lerp(albedo, Vec3f{0.92f, 0.93f, 0.96f}, snow);
  return makeVoxel(albedo, normal, alpha, empty);
}

// The octaves a box bound over radius r evaluates: octave o varies by at most its slope times r
// (the same NOISE_LIPSCHITZ / WAVE0 for every octave) and by at most its amplitude 2^-o
// NOISE_MAX_ABS, whichever is smaller: the first octaves are evaluated, the others bounded by
// their amplitudes unevaluated (sharper and cheaper for a box much wider than their wavelength).
GVDP_HD GVDP_INLINE int fbmBoundOctaves(float r, int octaves) {
  int k = 0;
  while (k < octaves &&
         NOISE_LIPSCHITZ / FBM_WAVE0 * r < NOISE_MAX_ABS / static_cast<float>(1 << k))
    ++k;
  return k;
}

// produceFbm flags a voxel empty when d <= -1.5 reach, d over the octaves of the voxel size.
GVDP_HD GVDP_INLINE bool fbmEmptyBox(Vec3d lo, Vec3d hi, float voxelSize, uint32_t seed) {
  BoxCentre b = boxCentre(lo, hi);
  int octaves = fbmOctaves(voxelSize);
  float reach = fbmEmptyReach(voxelSize, octaves);
  int k = fbmBoundOctaves(b.halfDiagonal, octaves);
  float dMax = densityBoundWithin(fbmDensity(b.centre, k, seed), b.halfDiagonal, fbmLipschitz(k),
                                  fbmHessian(k)) +
               (fbmRemainder(k) - fbmRemainder(octaves));
  // The height bound as perlin's: the octaves summed add at most their amplitudes.
  float dHeight =
      -static_cast<float>(lo.y) / FBM_HEIGHT + 2.0f * NOISE_MAX_ABS - fbmRemainder(octaves);
  return fminf(dMax, dHeight) + DENSITY_SLACK <= -1.5f * reach;
}

}  // namespace gvdp::detail
