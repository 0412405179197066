// The two disocclusion scenes (paper 4.1): `random-spheres`, spheres at random positions and
// sizes in a 3D grid of cells (uncorrelated disocclusion), and `aligned-spheres`, one sphere per
// cell at the cell centre (free sight to the horizon along the corridors, synchronised
// disocclusions). Each sphere stays inside its cell, so the distance to the cell border bounds
// the distance to every other sphere (conservativeness).
#pragma once

#include "gvdp/world/hash.h"
#include "gvdp/world/voxel.h"

namespace gvdp::detail {

constexpr float SPHERE_CELL = 6.0f;

struct SphereCell {
  Vec3f local;  // position inside the cell, in [0, SPHERE_CELL)
  Vec3i cell;
};

GVDP_HD GVDP_INLINE SphereCell sphereCellOf(Vec3d p) {
  double cx = floor(p.x / SPHERE_CELL), cy = floor(p.y / SPHERE_CELL),
         cz = floor(p.z / SPHERE_CELL);
  return {
      {static_cast<float>(p.x - cx * SPHERE_CELL), static_cast<float>(p.y - cy * SPHERE_CELL),
       static_cast<float>(p.z - cz * SPHERE_CELL)},
      {static_cast<int>(static_cast<long long>(cx)), static_cast<int>(static_cast<long long>(cy)),
       static_cast<int>(static_cast<long long>(cz))}};
}

// Opacity of a sphere seen through voxels of size voxelSize: a one-voxel band outside the
// surface (so that a sphere smaller than a voxel is never missed by the voxel centres), scaled
// down by the fraction of the voxel it covers.
GVDP_HD GVDP_INLINE float sphereAlpha(float distance, float radius, float voxelSize) {
  float area = fminf(1.0f, 2.0f * radius / voxelSize);
  return clamp01(1.0f - distance / voxelSize) * area * area;
}

GVDP_HD GVDP_INLINE float distanceToCellBorder(Vec3f l) {
  return fminf(fminf(fminf(l.x, SPHERE_CELL - l.x), fminf(l.y, SPHERE_CELL - l.y)),
               fminf(l.z, SPHERE_CELL - l.z));
}

struct Sphere {
  bool exists;
  Vec3f centre;  // relative to its cell's corner
  float radius;
  Vec3f albedo;
};

// `others`: a lower bound of the distance to the spheres of other cells.
GVDP_HD GVDP_INLINE VoxelSample produceSphere(const SphereCell& c, const Sphere& s, float others,
                                              float voxelSize) {
  float distance = s.exists ? length(c.local - s.centre) - s.radius : 1e30f;
  bool empty = fminf(distance, others) >= EMPTY_MARGIN_VOXELS * voxelSize;
  if (!s.exists) return {0u, empty};
  return makeVoxel(s.albedo, normalize(c.local - s.centre),
                   sphereAlpha(distance, s.radius, voxelSize), empty);
}

GVDP_HD GVDP_INLINE Vec3f paletteColour(float t) {
  // A cosine palette (saturated but not garish).
  return {0.5f + 0.4f * cosf(2.0f * PI * (t + 0.00f)), 0.5f + 0.4f * cosf(2.0f * PI * (t + 0.33f)),
          0.5f + 0.4f * cosf(2.0f * PI * (t + 0.67f))};
}

GVDP_HD GVDP_INLINE Sphere randomSphereOf(Vec3i cell, uint32_t seed) {
  int x = cell.x, y = cell.y, z = cell.z;
  Sphere s;
  s.exists = hash3Unit(x, y, z, seed) < 0.3f;
  s.radius = 0.6f + 1.6f * hash3Unit(x, y, z, seed + 1);
  float room = SPHERE_CELL - 2.0f * (s.radius + 0.05f);
  s.centre = {s.radius + 0.05f + room * hash3Unit(x, y, z, seed + 2),
              s.radius + 0.05f + room * hash3Unit(x, y, z, seed + 3),
              s.radius + 0.05f + room * hash3Unit(x, y, z, seed + 4)};
  s.albedo = paletteColour(hash3Unit(x, y, z, seed + 5));
  return s;
}

GVDP_HD GVDP_INLINE VoxelSample produceRandomSpheres(Vec3d p, float voxelSize, uint32_t seed) {
  SphereCell c = sphereCellOf(p);
  float reach = EMPTY_MARGIN_VOXELS * voxelSize;
  float others = distanceToCellBorder(c.local);
  // Near a border, the neighbours' actual spheres bound the distance (when the margin fits in
  // one cell; coarser voxels keep the border bound, and such bricks are never empty anyway).
  if (others < reach && reach <= SPHERE_CELL) {
    others = 1e30f;
    for (int n = 0; n < 27; ++n) {
      Vec3i d{n % 3 - 1, (n / 3) % 3 - 1, n / 9 - 1};
      if (d.x == 0 && d.y == 0 && d.z == 0) continue;
      Sphere s = randomSphereOf(c.cell + d, seed);
      if (!s.exists) continue;
      Vec3f centre = s.centre + Vec3f{d.x * SPHERE_CELL, d.y * SPHERE_CELL, d.z * SPHERE_CELL};
      others = fminf(others, length(c.local - centre) - s.radius);
    }
  }
  return produceSphere(c, randomSphereOf(c.cell, seed), others, voxelSize);
}

GVDP_HD GVDP_INLINE VoxelSample produceAlignedSpheres(Vec3d p, float voxelSize, uint32_t) {
  SphereCell c = sphereCellOf(p);
  const float RADIUS = 2.0f, HALF = 0.5f * SPHERE_CELL;
  float t = 0.13f * static_cast<float>((c.cell.x * 3 + c.cell.y * 5 + c.cell.z * 7) & 7);
  Sphere s{true, {HALF, HALF, HALF}, RADIUS, paletteColour(t)};
  // Every neighbour's sphere is HALF - RADIUS inside its cell.
  return produceSphere(c, s, distanceToCellBorder(c.local) + (HALF - RADIUS), voxelSize);
}

}  // namespace gvdp::detail
