// Level of detail from ray cones (paper 3.1, docs/DESIGN.md "Rendering"). Level L has voxel size
// v0 * 2^L and serves the distances where the cone footprint t * pixelAngle lies in
// (v(L-1), v(L)], so that a voxel is never smaller than a pixel. Samples are a lattice of
// one-voxel steps per level, restarted at each level's start: sample k of level L sits at
// t = start(L) + (k + 1/2) v(L). Sample positions are thus a function of the ray alone, which
// makes cached and direct renders comparable sample by sample.
#pragma once

#include "gvdp/base/defs.h"
#include "gvdp/base/vecmath.h"

namespace gvdp::detail {

// A level's voxel size and distance range, computed once per level a ray enters (the march
// keeps them in registers): the same values as Lod's functions, so the same samples.
struct LevelSpan {
  float voxelSize, start, end;
  float inverseVoxelSize;  // 1 / voxelSize (Lod::inverseVoxelSize)

  // A position in voxel units of the level (Lod::inVoxels).
  GVDP_HD Vec3f inVoxels(Vec3f p) const { return p * inverseVoxelSize; }
  // The brick of the level holding a position: floor(p / (BRICK_WIDTH voxelSize)) as a product
  // by the reciprocal scaled by a power of two (exact). Not inVoxels(p) / 8, the same value: the
  // compiler then kept inVoxels(p) for the sample's cell and sp's render kernel grew from 64 to 68
  // registers.
  GVDP_HD Vec3i brickOf(Vec3f p) const {
    return floorToInt(p * (inverseVoxelSize * (1.0f / BRICK_WIDTH)));
  }

  // Distance of lattice sample `step` of the level.
  GVDP_HD float sampleT(int step) const {
    return start + (static_cast<float>(step) + 0.5f) * voxelSize;
  }
};

// Lod::bias's largest value: the far distance 2^20 times nearer.
constexpr int MAX_FAR_BIAS = 20;

struct Lod {
  float voxelSize0;  // v0
  float pixelAngle;  // cone spread per unit distance (pixel footprint at t = 1)
  int levels;
  // A degraded frame's (tiles/tiled_frame.h): every level but the last serves distances 2^bias
  // times nearer, so the frame asks for coarser bricks; the last one still reaches the far
  // distance (the clipmap is the same) up to bias levels - 1, and each step beyond halves it.
  // 0: exact; the values are then bit for bit the same.
  int bias = 0;
  // Two quotients, once: the march's positions in voxels and its level ranges are then products
  // by powers of two, with the values the divisions gave (a rounding commutes with a scaling by a
  // power of two): v(L) / (pixelAngle 2^b) = reach0 2^(L - b), 1 / v(L) = (1 / v0) 2^-L.
  float inverseVoxelSize0 = 1.0f / voxelSize0;
  float reach0 = voxelSize0 / pixelAngle;  // where level 0 ends, bias 0

  // v0 2^L, exact (a product by a power of two): ldexpf's value without its cost.
  GVDP_HD float voxelSize(int level) const { return voxelSize0 * exp2i(level); }
  GVDP_HD float inverseVoxelSize(int level) const { return inverseVoxelSize0 * exp2i(-level); }
  // A position in voxel units of `level`: p / v(L) as Vec3f's division computes it, p * (1 / v(L)).
  GVDP_HD Vec3f inVoxels(Vec3f p, int level) const { return p * inverseVoxelSize(level); }
  // The cone spread that picks the levels (exact: a product by a power of two).
  GVDP_HD float levelAngle() const { return pixelAngle * exp2i(bias); }
  GVDP_HD float levelStart(int level) const {
    return level == 0 ? 0.0f : reach0 * exp2i(level - 1 - bias);
  }
  GVDP_HD float levelEnd(int level) const {
    if (level < levels - 1) return reach0 * exp2i(level - bias);
    int farBias = bias - (levels - 1);
    return reach0 * exp2i(farBias > 0 ? level - farBias : level);
  }
  GVDP_HD LevelSpan span(int level) const {
    float v = voxelSize(level);
    float inverse = inverseVoxelSize(level);
    return {v, levelStart(level), levelEnd(level), inverse};
  }
  GVDP_HD float sampleT(int level, int step) const { return span(level).sampleT(step); }
  // The first lattice step of `level` at or after distance t.
  GVDP_HD int firstStepAtOrAfter(int level, float t) const {
    return firstStepAtOrAfter(span(level), t);
  }
  // No division: an estimate through the reciprocal (inverseVoxelSize), then settled on the
  // lattice itself (sampleT), so the answer is exact whatever the estimate's rounding.
  GVDP_HD static int firstStepAtOrAfter(const LevelSpan& span, float t) {
    float k = ceilf((t - span.start) * span.inverseVoxelSize - 0.5f);
    int step = k > 0.0f ? static_cast<int>(k) : 0;
    if (step > 0 && span.sampleT(step - 1) >= t) return step - 1;
    return span.sampleT(step) < t ? step + 1 : step;
  }
  // The level whose distance range holds t (levels when beyond the last one).
  GVDP_HD int levelAt(float t) const {
    int level = 0;
    while (level < levels && t >= levelEnd(level)) ++level;
    return level;
  }
  // Farthest distance any sample can reach.
  GVDP_HD float farDistance() const { return levelEnd(levels - 1); }
};

// Clipmap width in bricks (paper 3.2): the window of level L must hold every sample of that
// level, which lies within levelEnd(L) + v(L) = v(L) (1/pixelAngle + 1) of the eye; the eye's
// brick is centred, so (W/2 - 1) bricks of 8 voxels must cover it. For 1500x1000 at 60 degrees
// this gives 328, close to the paper's 300.
inline int clipmapWidthFor(float pixelAngle) {
  int halfBricks = static_cast<int>(ceilf((1.0f / pixelAngle + 2.0f) / BRICK_WIDTH));
  return 2 * halfBricks + 2;
}

}  // namespace gvdp::detail
