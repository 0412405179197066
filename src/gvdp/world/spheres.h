// The two disocclusion scenes (paper 4.1): `random-spheres`, spheres at random positions and
// sizes in a 3D grid of cells (uncorrelated disocclusion), and `aligned-spheres`, one sphere per
// cell at the cell centre (free sight to the horizon along the corridors, synchronised
// disocclusions). Each sphere stays inside its cell, so the distance to the cell border bounds
// the distance to every other sphere (conservativeness).
#pragma once

#include "gvdp/world/hash.h"
#include "gvdp/world/voxel.h"

namespace gvdp {

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

GVDP_HD GVDP_INLINE VoxelSample produceSphere(const SphereCell& c, Vec3f centre, float radius,
                                              Vec3f albedo, bool exists, float voxelSize) {
  Vec3f l = c.local;
  float toBorder = fminf(fminf(fminf(l.x, SPHERE_CELL - l.x), fminf(l.y, SPHERE_CELL - l.y)),
                         fminf(l.z, SPHERE_CELL - l.z));
  float distance = exists ? length(l - centre) - radius : 1e30f;
  bool empty = fminf(distance, toBorder) >= EMPTY_MARGIN_VOXELS * voxelSize;
  if (!exists) return {0u, empty};
  return makeVoxel(albedo, normalize(l - centre), sphereAlpha(distance, radius, voxelSize), empty);
}

GVDP_HD GVDP_INLINE Vec3f paletteColour(float t) {
  // A cosine palette (saturated but not garish).
  return {0.5f + 0.4f * cosf(2.0f * PI * (t + 0.00f)), 0.5f + 0.4f * cosf(2.0f * PI * (t + 0.33f)),
          0.5f + 0.4f * cosf(2.0f * PI * (t + 0.67f))};
}

GVDP_HD GVDP_INLINE VoxelSample produceRandomSpheres(Vec3d p, float voxelSize, uint32_t seed) {
  SphereCell c = sphereCellOf(p);
  int x = c.cell.x, y = c.cell.y, z = c.cell.z;
  bool exists = hash3Unit(x, y, z, seed) < 0.3f;
  float radius = 0.6f + 1.6f * hash3Unit(x, y, z, seed + 1);
  float room = SPHERE_CELL - 2.0f * (radius + 0.05f);
  Vec3f centre{radius + 0.05f + room * hash3Unit(x, y, z, seed + 2),
               radius + 0.05f + room * hash3Unit(x, y, z, seed + 3),
               radius + 0.05f + room * hash3Unit(x, y, z, seed + 4)};
  return produceSphere(c, centre, radius, paletteColour(hash3Unit(x, y, z, seed + 5)), exists,
                       voxelSize);
}

GVDP_HD GVDP_INLINE VoxelSample produceAlignedSpheres(Vec3d p, float voxelSize, uint32_t) {
  SphereCell c = sphereCellOf(p);
  float half = 0.5f * SPHERE_CELL;
  float t = 0.13f * static_cast<float>((c.cell.x * 3 + c.cell.y * 5 + c.cell.z * 7) & 7);
  return produceSphere(c, {half, half, half}, 2.0f, paletteColour(t), true, voxelSize);
}

}  // namespace gvdp
