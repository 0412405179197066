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

// A cell's sphere; 70% of the cells have none, and their other fields are left zero unhashed (the
// neighbour loops of production and of the box bound look at `exists` first).
GVDP_HD GVDP_INLINE Sphere randomSphereOf(Vec3i cell, uint32_t seed) {
  int x = cell.x, y = cell.y, z = cell.z;
  Sphere s{};
  s.exists = hash3Unit(x, y, z, seed) < 0.3f;
  if (!s.exists) return s;
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

// random-spheres' box bound (the producer's emptyBox, world/producer.h). Its empty flag is exact
// while the margin fits in a cell (produceRandomSpheres: every sphere at least the margin away;
// beyond, flags keep the cell-border bound and bricks are never empty): the box is clear when
// no sphere of the cells that it and its margin overlap comes within the margin of it, at most
// SPHERE_BOX_CELLS cells looked at. SPHERE_SLACK covers the float distances of the flags.
constexpr int SPHERE_BOX_CELLS = 125;
constexpr double SPHERE_SLACK = 1e-3;

GVDP_HD GVDP_INLINE bool randomSpheresEmptyBox(Vec3d lo, Vec3d hi, float voxelSize, uint32_t seed) {
  double margin = EMPTY_MARGIN_VOXELS * static_cast<double>(voxelSize);
  if (margin > SPHERE_CELL) return false;
  margin += SPHERE_SLACK;
  auto cellOf = [](double a) { return static_cast<int>(floor(a / SPHERE_CELL)); };
  Vec3i c0{cellOf(lo.x - margin), cellOf(lo.y - margin), cellOf(lo.z - margin)};
  Vec3i c1{cellOf(hi.x + margin), cellOf(hi.y + margin), cellOf(hi.z + margin)};
  if ((c1.x - c0.x + 1) * (c1.y - c0.y + 1) * (c1.z - c0.z + 1) > SPHERE_BOX_CELLS) return false;
  auto gap = [](double c, double a, double b) { return c < a ? a - c : c > b ? c - b : 0.0; };
  for (int z = c0.z; z <= c1.z; ++z)
    for (int y = c0.y; y <= c1.y; ++y)
      for (int x = c0.x; x <= c1.x; ++x) {
        Sphere s = randomSphereOf({x, y, z}, seed);
        if (!s.exists) continue;
        double dx = gap(x * SPHERE_CELL + s.centre.x, lo.x, hi.x);
        double dy = gap(y * SPHERE_CELL + s.centre.y, lo.y, hi.y);
        double dz = gap(z * SPHERE_CELL + s.centre.z, lo.z, hi.z);
        double reach = s.radius + margin;
        if (dx * dx + dy * dy + dz * dz < reach * reach) return false;
      }
  return true;
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
