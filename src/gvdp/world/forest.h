// `forest` (paper 4.1): ground, trunks and ellipsoid crowns on a jittered grid of cells; foliage
// is a field of leaves, 16 leaf-disc SDF evaluations per voxel with sin-hash randoms, truncated
// by the crown, so that only several crowns together stop a ray. Coarse voxels smaller leaves
// fade into a mean foliage opacity.
//
// Conservativeness: every opacity term is nonzero only where a 1-Lipschitz distance lower bound
// (ground, trunk, crown, distance to the cell border) is below one voxel.
#pragma once

#include "gvdp/world/hash.h"
#include "gvdp/world/noise.h"
#include "gvdp/world/voxel.h"

namespace gvdp::detail {

constexpr float TREE_CELL = 14.0f;
constexpr float LEAF_CELL = 0.6f, LEAF_RADIUS = 0.16f, LEAF_THICKNESS = 0.01f;
constexpr float FOLIAGE_SIGMA = 0.18f;  // mean foliage opacity per unit length
constexpr float GROUND_AMPLITUDE = 1.5f, GROUND_WAVE = 40.0f;

// Trees stand between these heights (trunks from -3 to at most 8, crowns to 8 + 1.3 * 5).
constexpr float TREE_BOTTOM = -3.0f, TREE_TOP = 8.0f + 1.3f * 5.0f, TRUNK_MAX_TOP = 8.0f;
constexpr float GROUND_LIPSCHITZ = 1.01f;  // sqrt(1 + (amp * NOISE_LIPSCHITZ / wave)^2)

struct Tree {
  bool exists;
  Vec3f base;  // trunk axis at y = 0, relative to the cell corner
  float trunkRadius, trunkTop;
  Vec3f crownCentre, crownRadii;
};

GVDP_HD GVDP_INLINE Tree treeOfCell(int cx, int cz, uint32_t seed) {
  Tree t;
  t.exists = hash3Unit(cx, 0, cz, seed) < 0.85f;
  float jx = hash3Unit(cx, 1, cz, seed) * 3.0f - 1.5f;
  float jz = hash3Unit(cx, 2, cz, seed) * 3.0f - 1.5f;
  t.base = {0.5f * TREE_CELL + jx, 0.0f, 0.5f * TREE_CELL + jz};
  t.trunkRadius = 0.3f + 0.2f * hash3Unit(cx, 3, cz, seed);
  t.trunkTop = 5.0f + 3.0f * hash3Unit(cx, 4, cz, seed);
  float rxz = 3.0f + 1.5f * hash3Unit(cx, 5, cz, seed);  // crown stays >= 1 inside the cell
  float ry = 3.5f + 1.5f * hash3Unit(cx, 6, cz, seed);
  t.crownRadii = {rxz, ry, rxz};
  t.crownCentre = {t.base.x, t.trunkTop + 0.3f * ry, t.base.z};
  return t;
}

GVDP_HD GVDP_INLINE float groundHeight(Vec3d p, uint32_t seed, Vec3f* normal) {
  NoiseSample n = gradientNoise({p.x / GROUND_WAVE, 0.37, p.z / GROUND_WAVE}, seed + 7);
  float k = GROUND_AMPLITUDE / GROUND_WAVE;
  *normal = normalize(Vec3f{-n.grad.x * k, 1.0f, -n.grad.z * k});
  return GROUND_AMPLITUDE * n.value;
}

// A thin disc: distance to its rim region and to its plane.
GVDP_HD GVDP_INLINE float leafDistance(Vec3f q, Vec3f n) {
  float dn = dot(q, n);
  float radial = sqrtf(fmaxf(dot(q, q) - dn * dn, 0.0f));
  float a = radial - LEAF_RADIUS, b = fabsf(dn) - LEAF_THICKNESS;
  float ax = fmaxf(a, 0.0f), bx = fmaxf(b, 0.0f);
  return sqrtf(ax * ax + bx * bx) + fminf(fmaxf(a, b), 0.0f);
}

struct LeafHit {
  float distance;
  Vec3f normal, albedo;
};

// The 16 leaves of the 2x2x2 leaf cells nearest to p (two candidates per cell).
GVDP_HD GVDP_INLINE LeafHit nearestLeaf(Vec3d p) {
  double gx = p.x / LEAF_CELL - 0.5, gy = p.y / LEAF_CELL - 0.5, gz = p.z / LEAF_CELL - 0.5;
  double bx = floor(gx), by = floor(gy), bz = floor(gz);
  // Position inside the 2x2x2 block, in leaf-cell units, and the block's wrapped coordinates
  // (sinf needs small arguments; the period of 1024 cells is far beyond any view).
  Vec3f f{static_cast<float>(gx - bx) + 0.5f, static_cast<float>(gy - by) + 0.5f,
          static_cast<float>(gz - bz) + 0.5f};
  float wx = static_cast<float>(bx - 1024.0 * floor(bx / 1024.0));
  float wy = static_cast<float>(by - 1024.0 * floor(by / 1024.0));
  float wz = static_cast<float>(bz - 1024.0 * floor(bz / 1024.0));
  LeafHit best{1e30f, {0, 1, 0}, {0.2f, 0.4f, 0.1f}};
  for (int c = 0; c < 8; ++c) {
    float ox = static_cast<float>(c & 1), oy = static_cast<float>((c >> 1) & 1);
    float oz = static_cast<float>(c >> 2);
    for (int k = 0; k < 2; ++k) {
      float fk = static_cast<float>(k);
      float cx = wx + ox, cy = wy + oy, cz = wz + oz;
      Vec3f centre{ox + sinHash(cx, cy, cz, fk), oy + sinHash(cy, cz, cx, fk + 2.0f),
                   oz + sinHash(cz, cx, cy, fk + 4.0f)};
      float theta = 2.0f * PI * sinHash(cx, cz, cy, fk + 6.0f);
      float cosPhi = sinHash(cz, cy, cx, fk + 8.0f);  // normals in the upper hemisphere
      float sinPhi = sqrtf(fmaxf(1.0f - cosPhi * cosPhi, 0.0f));
      Vec3f n{sinPhi * cosf(theta), cosPhi, sinPhi * sinf(theta)};
      float d = leafDistance((f - centre) * LEAF_CELL, n);
      if (d < best.distance) {
        float shade = sinHash(cx, cy, cz, fk + 10.0f);
        best = {d, n, {0.16f + 0.18f * shade, 0.36f + 0.20f * shade, 0.08f + 0.05f * shade}};
      }
    }
  }
  return best;
}

// The distance lower bounds of a point against the tree of one cell (corner cellX, cellZ in
// cells), the ground, and the other cells' trees. Each is 1-Lipschitz in p over all space, the
// point in the cell or not (the ground's by GROUND_LIPSCHITZ, the crown's ellipsoid scaled by
// its smallest radius, the others' a max of planes): forestEmptyBox relies on it.
struct ForestDistances {
  Tree tree;
  Vec3f q;  // p relative to the cell's corner
  Vec3f groundNormal, crownQ;
  float groundLB, trunk, crown, others;

  GVDP_HD float nearest() const { return fminf(fminf(groundLB, trunk), fminf(crown, others)); }
};

GVDP_HD GVDP_INLINE ForestDistances forestDistances(Vec3d p, double cellX, double cellZ,
                                                    uint32_t seed) {
  ForestDistances f;
  f.tree = treeOfCell(static_cast<int>(static_cast<long long>(cellX)),
                      static_cast<int>(static_cast<long long>(cellZ)), seed);
  const Tree& tree = f.tree;
  Vec3f q{static_cast<float>(p.x - cellX * TREE_CELL), static_cast<float>(p.y),
          static_cast<float>(p.z - cellZ * TREE_CELL)};
  f.q = q;
  // Other cells' trees stay 1 unit inside their cells and within a band of heights.
  float toBorder = fminf(fminf(q.x, TREE_CELL - q.x), fminf(q.z, TREE_CELL - q.z)) + 1.0f;
  f.others = fmaxf(toBorder, fmaxf(q.y - TREE_TOP, TREE_BOTTOM - q.y));
  float gy = groundHeight(p, seed, &f.groundNormal);
  f.groundLB = (q.y - gy) / GROUND_LIPSCHITZ;
  f.trunk = 1e30f;
  f.crown = 1e30f;
  f.crownQ = {0, 1, 0};
  if (tree.exists) {
    Vec3f t = q - tree.base;
    float radial = sqrtf(t.x * t.x + t.z * t.z) - tree.trunkRadius;
    float vertical = fmaxf(-3.0f - t.y, t.y - tree.trunkTop);
    float rx = fmaxf(radial, 0.0f), vx = fmaxf(vertical, 0.0f);
    f.trunk = sqrtf(rx * rx + vx * vx) + fminf(fmaxf(radial, vertical), 0.0f);
    f.crownQ = (q - tree.crownCentre) *
               Vec3f{1.0f / tree.crownRadii.x, 1.0f / tree.crownRadii.y, 1.0f / tree.crownRadii.z};
    f.crown = (length(f.crownQ) - 1.0f) * minComponent(tree.crownRadii);
  }
  return f;
}

GVDP_HD GVDP_INLINE VoxelSample produceForest(Vec3d p, float voxelSize, uint32_t seed) {
  ForestDistances f = forestDistances(p, floor(p.x / TREE_CELL), floor(p.z / TREE_CELL), seed);
  const Tree& tree = f.tree;
  Vec3f q = f.q, groundNormal = f.groundNormal, crownQ = f.crownQ;
  float groundLB = f.groundLB, trunk = f.trunk, crown = f.crown;
  float nearest = f.nearest();
  bool empty = nearest >= EMPTY_MARGIN_VOXELS * voxelSize;

  // Solid part: ground or trunk.
  float groundAlpha = coverage(groundLB, voxelSize), trunkAlpha = coverage(trunk, voxelSize);
  Vec3f solidColour{0, 0, 0};
  float solidAlpha = fmaxf(groundAlpha, trunkAlpha);
  if (solidAlpha > 0.0f) {
    if (trunkAlpha >= groundAlpha) {
      Vec3f n = normalize(Vec3f{q.x - tree.base.x, 0.0f, q.z - tree.base.z});
      solidColour = bakeShading({0.30f, 0.20f, 0.12f}, n);
    } else {
      float tint = 0.5f + 0.5f * sinf(static_cast<float>(p.x) * 0.3f) *
                              sinf(static_cast<float>(p.z) * 0.23f);
      solidColour = bakeShading(lerp(Vec3f{0.25f, 0.36f, 0.12f}, Vec3f{0.36f, 0.30f, 0.16f}, tint),
                                groundNormal);
    }
  }

  // Foliage, only where the crown lets it be (the truncation of the paper's leaf field).
  float crownAlpha = coverage(crown, voxelSize);
  float leafAlpha = 0.0f;
  Vec3f leafColour{0, 0, 0};
  if (crownAlpha > 0.0f) {
    LeafHit leaf = nearestLeaf(p);
    float fine = coverage(leaf.distance, voxelSize);
    float mean = 1.0f - expf(-FOLIAGE_SIGMA * voxelSize);
    float w = smoothstep(0.5f * LEAF_RADIUS, 2.0f * LEAF_RADIUS, voxelSize);
    leafAlpha = lerp(fine, mean, w) * crownAlpha;
    Vec3f n = w < 0.5f ? leaf.normal : normalize(crownQ);
    leafColour = bakeShading(leaf.albedo, n);
  }

  float alpha = solidAlpha + leafAlpha * (1.0f - solidAlpha);
  if (alpha <= 0.0f) return {0u, empty};
  Vec3f premultiplied = solidColour * solidAlpha + leafColour * (leafAlpha * (1.0f - solidAlpha));
  return {packRgba8(premultiplied, alpha), empty};
}

// A box is empty (every voxel flagged: produceForest's nearest >= 3 voxels) where
// - it lies above every tree and the ground (the sky): at height y >= TREE_TOP each distance
//   bound of produceForest is at least the smallest of (y - ground max) / GROUND_LIPSCHITZ,
//   y - TRUNK_MAX_TOP, y - TREE_TOP and, for a crown, (y - TREE_TOP) * min radius / vertical
//   radius >= 0.6 (y - TREE_TOP);
// - or, for each tree cell it overlaps (at most FOREST_BOX_CELLS), the cell's nearest bound at
//   the box's centre exceeds the margin by half the box's diagonal (1-Lipschitz,
//   forestDistances): the air between trunks and crowns.
// 1e-3 covers float rounding.
constexpr int FOREST_BOX_CELLS = 4;

GVDP_HD GVDP_INLINE bool forestEmptyBox(Vec3d lo, Vec3d hi, float voxelSize, uint32_t seed) {
  float margin = EMPTY_MARGIN_VOXELS * voxelSize + 1e-3f;
  float y = static_cast<float>(lo.y);
  if (y >= TREE_TOP) {
    float ground = (y - GROUND_AMPLITUDE * NOISE_MAX_ABS) / GROUND_LIPSCHITZ;
    if (fminf(fminf(ground, y - TRUNK_MAX_TOP), 0.6f * (y - TREE_TOP)) >= margin) return true;
  }
  double x0 = floor(lo.x / TREE_CELL), x1 = floor(hi.x / TREE_CELL);
  double z0 = floor(lo.z / TREE_CELL), z1 = floor(hi.z / TREE_CELL);
  if ((x1 - x0 + 1.0) * (z1 - z0 + 1.0) > FOREST_BOX_CELLS) return false;
  Vec3d c{0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y), 0.5 * (lo.z + hi.z)};
  double dx = hi.x - lo.x, dy = hi.y - lo.y, dz = hi.z - lo.z;
  float r = static_cast<float>(0.5 * sqrt(dx * dx + dy * dy + dz * dz));
  for (double cx = x0; cx <= x1; cx += 1.0)
    for (double cz = z0; cz <= z1; cz += 1.0)
      if (forestDistances(c, cx, cz, seed).nearest() - r < margin) return false;
  return true;
}

}  // namespace gvdp::detail
