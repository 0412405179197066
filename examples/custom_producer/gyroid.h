// A user-defined world: a ball of gyroid, the sheet sin x cos y + sin y cos z + sin z cos x = 0
// thickened to a shell and cut by a sphere, as a gvdp producer (gvdp/producer.h). Nothing here
// is built into gvdp: the renderer is instantiated for this type in the user's translation unit
// (gvdp/make_renderer.h).
#pragma once

#include "gvdp/producer.h"

struct Gyroid {
  float radius;     // of the ball, centred at the origin, world units
  float period;     // world units per gyroid cell (2 pi in gyroid coordinates)
  float thickness;  // half-thickness of the shell, in units of f
  float finest;     // level-0 voxel size, world units

  // A lower bound of the distance to matter, 1-Lipschitz, and the outward direction there.
  // f is sqrt(6)-Lipschitz in gyroid coordinates (each partial derivative is at most sqrt 2),
  // so (|f| - thickness) / (sqrt 6 k) bounds the distance to the shell; the ball's signed
  // distance is exact; the larger of two such bounds bounds the distance to their intersection.
  GVDP_HD float distanceBound(gvdp::Vec3d p, gvdp::Vec3f* outward) const {
    float k = 2.0f * gvdp::PI / period;
    // Reduce to one period first: float keeps its precision far from the origin.
    auto wrap = [&](double x) { return static_cast<float>(x - period * floor(x / period)) * k; };
    float x = wrap(p.x), y = wrap(p.y), z = wrap(p.z);
    float sx = sinf(x), cx = cosf(x), sy = sinf(y), cy = cosf(y), sz = sinf(z), cz = cosf(z);
    float f = sx * cy + sy * cz + sz * cx;
    float shell = (fabsf(f) - thickness) / (2.4494897f * k);
    float r = static_cast<float>(sqrt(p.x * p.x + p.y * p.y + p.z * p.z));
    float ball = r - radius;
    if (outward) {
      gvdp::Vec3f g = ball > shell
                          ? gvdp::Vec3f{static_cast<float>(p.x), static_cast<float>(p.y),
                                        static_cast<float>(p.z)}
                          : gvdp::Vec3f{cx * cy - sz * sx, cy * cz - sx * sy, cz * cx - sy * sz} *
                                (f < 0.0f ? -1.0f : 1.0f);
      float l = gvdp::length(g);
      *outward = l > 1e-6f ? g * (1.0f / l) : gvdp::Vec3f{0.0f, 1.0f, 0.0f};
    }
    return fmaxf(shell, ball);
  }

  GVDP_HD gvdp::VoxelSample voxel(gvdp::Vec3d p, float voxelSize) const {
    gvdp::Vec3f normal;
    float d = distanceBound(p, &normal);
    bool empty = d >= gvdp::EMPTY_MARGIN_VOXELS * voxelSize;
    // A voxel wider than the shell is only partly covered by it: scale by the shell's share.
    float width = 2.0f * thickness * period / (2.0f * gvdp::PI * 2.4494897f);
    float alpha = gvdp::coverage(d, voxelSize) * fminf(1.0f, 2.0f * width / voxelSize);
    if (alpha <= 0.0f) return {0u, empty};
    // Colour bands across the lattice, so that motion through it reads.
    float t = static_cast<float>((p.x + p.y + p.z) / period);
    gvdp::Vec3f albedo{0.55f + 0.35f * sinf(t), 0.55f + 0.35f * sinf(t + 2.1f),
                       0.55f + 0.35f * sinf(t + 4.2f)};
    return gvdp::makeVoxel(albedo, normal, alpha, empty);
  }

  // The bound is 1-Lipschitz: the box is empty when its centre is farther from matter than its
  // half-diagonal plus the empty margin (and 1e-4 period of slack for float rounding).
  GVDP_HD bool emptyBox(gvdp::Vec3d lo, gvdp::Vec3d hi, float voxelSize) const {
    gvdp::Vec3d c{0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y), 0.5 * (lo.z + hi.z)};
    double dx = hi.x - lo.x, dy = hi.y - lo.y, dz = hi.z - lo.z;
    float halfDiagonal = static_cast<float>(0.5 * sqrt(dx * dx + dy * dy + dz * dz));
    return distanceBound(c, nullptr) - halfDiagonal - 1e-4f * period >=
           gvdp::EMPTY_MARGIN_VOXELS * voxelSize;
  }

  // Optional: a brick whose box the bound refuses is tested again as 3^3 sub-boxes, whose
  // half-diagonals are a third of its own (gvdp/world/producer.h: boundSplit).
  GVDP_HD int boundSplit() const { return 3; }

  GVDP_HD float voxelSize0() const { return finest; }
};

static_assert(gvdp::Producer<Gyroid>);
