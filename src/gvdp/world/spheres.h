// The two disocclusion scenes (paper 4.1): `random-spheres`, spheres at random positions and
// sizes in a 3D grid of cells (uncorrelated disocclusion), and `aligned-spheres`, one sphere per
// cell at the cell centre (free sight to the horizon along the corridors, synchronised
// disocclusions). Each sphere stays inside its cell, so the distance to the cell border bounds
// the distance to every other sphere (conservativeness).
#pragma once

#include "gvdp/base/bits.h"
#include "gvdp/base/rounded_math.h"
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

// |v| with its products fused in one fixed order on the GPU, y y first: nvcc may contract
// x x + y y + z z either way and chooses by the code around it (a change to the neighbour loop
// once changed a few voxels by one unit). The spheres' distances and normals use it, so that the
// worlds do not depend on the code around them.
GVDP_HD GVDP_INLINE float sphereLength(Vec3f v) {
#if GVDP_IS_GPU_CODE
  return sqrtf(fmaf(v.z, v.z, fmaf(v.x, v.x, roundedMul(v.y, v.y))));
#else
  return length(v);
#endif
}

GVDP_HD GVDP_INLINE Vec3f sphereNormal(Vec3f v) {
  float l = sphereLength(v);
  return l > 0.0f ? v * (1.0f / l) : Vec3f{0.0f, 1.0f, 0.0f};
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
};

// The distance from c to its cell's sphere s (1e30 when the cell has none).
GVDP_HD GVDP_INLINE float sphereDistance(const SphereCell& c, const Sphere& s) {
  return s.exists ? sphereLength(c.local - s.centre) - s.radius : 1e30f;
}

// The voxel of sphere s (its cell's, at `distance`: sphereDistance; of colour albedo(), asked
// only for a voxel it covers). `others`: the distance to the spheres of other cells, or a value
// on the same side of the margin (it decides the empty flag only).
template <class Albedo>
GVDP_HD GVDP_INLINE VoxelSample produceSphere(const SphereCell& c, const Sphere& s, float distance,
                                              float others, float voxelSize, Albedo albedo) {
  bool empty = fminf(distance, others) >= EMPTY_MARGIN_VOXELS * voxelSize;
  if (!s.exists) return {0u, empty};
  float alpha = sphereAlpha(distance, s.radius, voxelSize);
  if (alpha <= 0.0f) return {0u, empty};
  return makeVoxel(albedo(), sphereNormal(c.local - s.centre), alpha, empty);
}

GVDP_HD GVDP_INLINE Vec3f paletteColour(float t) {
  // A cosine palette (saturated but not garish).
  return {0.5f + 0.4f * cosf(2.0f * PI * (t + 0.00f)), 0.5f + 0.4f * cosf(2.0f * PI * (t + 0.33f)),
          0.5f + 0.4f * cosf(2.0f * PI * (t + 0.67f))};
}

// A cell's sphere; 70% of the cells have none, and their other fields are left zero unhashed (the
// neighbour loops of production and of the box bound look at `exists` first). Its colour is
// hashed apart (randomSphereAlbedo), only for the voxels a sphere covers.
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
  return s;
}

GVDP_HD GVDP_INLINE Vec3f randomSphereAlbedo(Vec3i cell, uint32_t seed) {
  return paletteColour(hash3Unit(cell.x, cell.y, cell.z, seed + 5));
}

// The neighbour offset (-1, 0 or 1) along one axis whose cells can come within `reach` of local
// coordinate l: a bit each for -1, 0, +1 (0 always). Every sphere lies more than 0.05 inside its
// cell, so a neighbour cell farther than reach along one axis holds no sphere within reach.
GVDP_HD GVDP_INLINE uint32_t neighbourSides(float l, float reach) {
  return 2u | (l < reach ? 1u : 0u) | (SPHERE_CELL - l < reach ? 4u : 0u);
}

// The neighbour cells n (0-26: offset n % 3 - 1, n / 3 % 3 - 1, n / 9 - 1) within reach along
// every axis, as bits, the cell itself left out: each axis's sides (neighbourSides) spread over
// the 27.
GVDP_HD GVDP_INLINE uint32_t neighboursWithin(uint32_t sx, uint32_t sy, uint32_t sz) {
  uint32_t x = sx * 0x01249249u;  // sx at every third bit: n % 3
  uint32_t y9 = (sy & 1u ? 0x7u : 0u) | (sy & 2u ? 0x38u : 0u) | (sy & 4u ? 0x1c0u : 0u);
  uint32_t y = y9 * 0x40201u;  // y9 in each group of nine: n / 3 % 3
  uint32_t z = (sz & 1u ? 0x1ffu : 0u) | (sz & 2u ? 0x3fe00u : 0u) | (sz & 4u ? 0x7fc0000u : 0u);
  return x & y & z & ~(1u << 13);
}

// Whether a sphere of the neighbour cells comes within reach of c (reach <= SPHERE_CELL). Only
// the neighbours within reach along every axis can (neighbourSides), visited in the order of n;
// the loop ends at the first. (A loop over all 26 that skipped the others was 22% of the warp
// instructions of a random-spheres frame that produced 268 000 bricks: H100, BENCHMARKS.md.)
GVDP_HD GVDP_INLINE bool neighbourSphereWithin(const SphereCell& c, float reach, uint32_t seed) {
  for (uint32_t m =
           neighboursWithin(neighbourSides(c.local.x, reach), neighbourSides(c.local.y, reach),
                            neighbourSides(c.local.z, reach));
       m != 0u; m &= m - 1u) {
    int n = lowestBit(m);
    Vec3i d{n % 3 - 1, (n / 3) % 3 - 1, n / 9 - 1};
    Sphere s = randomSphereOf(c.cell + d, seed);
    if (!s.exists) continue;
    Vec3f centre = s.centre + Vec3f{d.x * SPHERE_CELL, d.y * SPHERE_CELL, d.z * SPHERE_CELL};
    if (sphereLength(c.local - centre) - s.radius < reach) return true;
  }
  return false;
}

// The empty flag is min(own sphere's distance, others) >= reach, and `others` serves nothing
// else: near a border (when the margin fits in one cell; coarser voxels keep the border bound,
// and such bricks are never empty anyway) the neighbours' spheres decide it, looked at only when
// the own sphere leaves it open.
GVDP_HD GVDP_INLINE VoxelSample produceRandomSpheres(Vec3d p, float voxelSize, uint32_t seed) {
  SphereCell c = sphereCellOf(p);
  float reach = EMPTY_MARGIN_VOXELS * voxelSize;
  Sphere own = randomSphereOf(c.cell, seed);
  float distance = sphereDistance(c, own), others = distanceToCellBorder(c.local);
  if (distance >= reach && others < reach && reach <= SPHERE_CELL)
    others = neighbourSphereWithin(c, reach, seed) ? 0.0f : 1e30f;
  return produceSphere(c, own, distance, others, voxelSize,
                       [&] { return randomSphereAlbedo(c.cell, seed); });
}

// random-spheres' box bound (the producer's emptyBox, world/producer.h). Its empty flag is exact
// while the margin fits in a cell (produceRandomSpheres: every sphere at least the margin away;
// beyond, flags keep the cell-border bound and bricks are never empty): the box is clear when
// no sphere of the cells that it and its margin overlap comes within the margin of it, at most
// SPHERE_BOX_CELLS cells looked at. SPHERE_SLACK covers the float distances of the flags. Part
// `part` of `parts` looks at every parts-th of those cells (world/producer.h: emptyBoxPart).
constexpr int SPHERE_BOX_CELLS = 125;
constexpr double SPHERE_SLACK = 1e-3;

GVDP_HD GVDP_INLINE bool randomSpheresEmptyBoxPart(Vec3d lo, Vec3d hi, float voxelSize,
                                                   uint32_t seed, int part, int parts) {
  double margin = EMPTY_MARGIN_VOXELS * static_cast<double>(voxelSize);
  if (margin > SPHERE_CELL) return false;
  margin += SPHERE_SLACK;
  auto cellOf = [](double a) { return static_cast<int>(floor(a / SPHERE_CELL)); };
  Vec3i c0{cellOf(lo.x - margin), cellOf(lo.y - margin), cellOf(lo.z - margin)};
  Vec3i c1{cellOf(hi.x + margin), cellOf(hi.y + margin), cellOf(hi.z + margin)};
  int nx = c1.x - c0.x + 1, ny = c1.y - c0.y + 1, cells = nx * ny * (c1.z - c0.z + 1);
  if (cells > SPHERE_BOX_CELLS) return false;
  auto gap = [](double c, double a, double b) { return c < a ? a - c : c > b ? c - b : 0.0; };
  // Cell k = (x - c0.x) + nx ((y - c0.y) + ny (z - c0.z)), from part on by steps of parts: the
  // step's digits added with carries (divisions by nx and ny once, not for every cell).
  Vec3i step{parts % nx, parts / nx % ny, parts / (nx * ny)};
  int x = c0.x + part % nx, y = c0.y + part / nx % ny, z = c0.z + part / (nx * ny);
  for (int k = part; k < cells; k += parts, x += step.x, y += step.y, z += step.z) {
    if (x > c1.x) x -= nx, ++y;
    if (y > c1.y) y -= ny, ++z;
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

GVDP_HD GVDP_INLINE bool randomSpheresEmptyBox(Vec3d lo, Vec3d hi, float voxelSize, uint32_t seed) {
  return randomSpheresEmptyBoxPart(lo, hi, voxelSize, seed, 0, 1);
}

// aligned-spheres: a sphere of radius ALIGNED_RADIUS at every cell's centre.
constexpr float ALIGNED_RADIUS = 2.0f;

// The distance from a point of a cell (local, its offset from the cell's centre) to the nearest
// sphere of the other cells: the centres are a lattice, so the nearest other centre is one cell
// over along the axis where the point is farthest from its own centre (moving along another axis
// instead, or along two, adds (6 - |a|)^2 - a^2 >= 0 for an |a| <= 3 no larger).
GVDP_HD GVDP_INLINE float alignedOthersDistance(Vec3f a) {
  Vec3f m = abs(a);
  if (m.x >= m.y && m.x >= m.z)
    a.x = SPHERE_CELL - m.x;
  else if (m.y >= m.z)
    a.y = SPHERE_CELL - m.y;
  else
    a.z = SPHERE_CELL - m.z;
  return sphereLength(a) - ALIGNED_RADIUS;
}

GVDP_HD GVDP_INLINE VoxelSample produceAlignedSpheres(Vec3d p, float voxelSize, uint32_t) {
  SphereCell c = sphereCellOf(p);
  const float HALF = 0.5f * SPHERE_CELL;
  float t = 0.13f * static_cast<float>((c.cell.x * 3 + c.cell.y * 5 + c.cell.z * 7) & 7);
  Sphere s{true, {HALF, HALF, HALF}, ALIGNED_RADIUS};
  return produceSphere(c, s, sphereDistance(c, s), alignedOthersDistance(c.local - s.centre),
                       voxelSize, [&] { return paletteColour(t); });
}

// aligned-spheres' box bound: the sphere nearest a box has the centre nearest it along each axis
// apart (a lattice), and the flags hold exact distances (above): the box is clear when that
// centre's distance less the radius reaches the margin.
GVDP_HD GVDP_INLINE bool alignedSpheresEmptyBox(Vec3d lo, Vec3d hi, float voxelSize, uint32_t) {
  auto gap = [](double a, double b) {  // from [a, b] to the nearest centre 6 k + 3
    double below = 0.5 * SPHERE_CELL + SPHERE_CELL * floor((a - 0.5 * SPHERE_CELL) / SPHERE_CELL);
    double above = below + SPHERE_CELL;
    return above <= b ? 0.0 : fmin(a - below, above - b);
  };
  double gx = gap(lo.x, hi.x), gy = gap(lo.y, hi.y), gz = gap(lo.z, hi.z);
  return sqrt(gx * gx + gy * gy + gz * gz) - ALIGNED_RADIUS >=
         EMPTY_MARGIN_VOXELS * static_cast<double>(voxelSize) + SPHERE_SLACK;
}

}  // namespace gvdp::detail
