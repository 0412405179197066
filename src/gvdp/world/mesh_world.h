// A triangle mesh as a world (issue 15): the producer (world/producer.h) of a closed mesh placed
// at the origin (mesh/mesh.h placeMesh: its longest side MESH_PLACED_SIZE), alone or repeated on
// a lattice in x and z (a field of copies). A voxel's opacity comes from the signed distance to
// the nearest surface (coverage(): a one-voxel-wide transition), its sign from the pseudonormal of
// the nearest feature (mesh/mesh_normals.h), its colour the shaded albedo at the interpolated
// vertex normal. The distance is needed within a voxel of the surface only: points farther are
// inside (opaque) or outside (clear) by a ray cast (insideByRay), since a nearest query over the
// margin would visit much of the hierarchy at coarse levels. Distances and box tests go through
// the distance hierarchy (mesh/mesh_bvh.h: coarse voxels take its surfels), ray casts through
// the kd-tree (mesh/surface_queries.h). Exactness of skipping: the empty flag is raised only when
// the point is outside and no triangle's box meets the cube of EMPTY_MARGIN_VOXELS voxels around
// it, and emptyBox() only when no triangle's box meets the box grown by that margin and the box is
// outside: the same test for every point of the box.
#pragma once

#include <cstdint>

#include "gvdp/base/camera.h"
#include "gvdp/mesh/surface_queries.h"
#include "gvdp/world/hash.h"
#include "gvdp/world/producer.h"
#include "gvdp/world/spheres.h"  // paletteColour

namespace gvdp::detail {

constexpr float MESH_VOXEL_SIZE0 = 1.0f / 1024.0f;  // a placed model is ~1024 finest voxels long
constexpr float MESH_LATTICE_MIN = 1.5f;            // copies at least half a model apart
constexpr float MESH_LATTICE_MAX = 1000.0f;
constexpr int MESH_BOX_CELLS = 16;          // emptyBox looks at most at this many copies
constexpr double MESH_SLACK = 1e-4;         // covers the float distances of the flags
constexpr float MESH_SURFEL_VOXELS = 1.0f;  // nodes this many voxels wide count as surfels
constexpr float MESH_SPEED = 0.02f;         // world units per frame along the camera paths

// A point of the world in the frame of the copy of lattice cell (cx, cz): the copy's model sits
// at the cell's centre (cx, 0, cz) * lattice.
struct MeshCopy {
  int cx, cz;
  Vec3f local;
};

struct MeshWorld {
  SurfaceView surface;
  float finest;
  float lattice;  // 0: one model; else the period of the x-z lattice of copies

  GVDP_HD MeshCopy copyOf(Vec3d p, int dx = 0, int dz = 0) const {
    if (lattice == 0.0f) return {0, 0, toFloat(p)};
    double period = lattice;
    int cx = static_cast<int>(floor(p.x / period + 0.5)) + dx;
    int cz = static_cast<int>(floor(p.z / period + 0.5)) + dz;
    return {cx, cz, toFloat(Vec3d{p.x - cx * period, p.y, p.z - cz * period})};
  }
  GVDP_HD Vec3f albedo(int cx, int cz) const {
    if (lattice == 0.0f) return {0.80f, 0.74f, 0.62f};
    return lerp(Vec3f{0.80f, 0.74f, 0.62f}, paletteColour(hash3Unit(cx, 0, cz, 17u)), 0.6f);
  }

  GVDP_HD VoxelSample voxel(Vec3d p, float voxelSize) const {
    // The nearest triangle within a voxel (where coverage() is between 0 and 1 and the shading
    // normal matters) among the copies whose box comes that near.
    NearestTriangle best{2.25f * voxelSize * voxelSize, KD_NO_HIT, {}};
    MeshCopy at = copyOf(p);
    int reach = lattice == 0.0f ? 0 : 1;
    for (int dz = -reach; dz <= reach; ++dz)
      for (int dx = -reach; dx <= reach; ++dx) {
        MeshCopy c = copyOf(p, dx, dz);
        if (!(boxDistanceSq(c.local, surface.tree.bounds) < best.distanceSq)) continue;
        NearestTriangle t =
            nearestTriangle(c.local, surface, best.distanceSq, MESH_SURFEL_VOXELS * voxelSize);
        if (t.found()) {
          best = t;
          at = c;
        }
      }
    if (best.found()) {
      float d = sqrtf(best.distanceSq);
      float signedDistance = insideOf(at.local, surface, best) ? -d : d;
      Vec3f normal = shadingNormal(surface, best, at.local);
      return makeVoxel(albedo(at.cx, at.cz), normal, coverage(signedDistance, voxelSize), false);
    }
    // Farther than a voxel from every surface: opaque inside (only the own copy's box can hold
    // the point: copies' boxes are disjoint), else clear, and empty when no triangle's box comes
    // within the margin (the test emptyBox() makes for a whole box).
    if (boxDistanceSq(at.local, surface.tree.bounds) == 0.0f && insideByRay(at.local, surface))
      return makeVoxel(albedo(at.cx, at.cz), Vec3f{0.0f, 1.0f, 0.0f}, 1.0f, false);
    float margin = EMPTY_MARGIN_VOXELS * voxelSize;
    Vec3f m{margin, margin, margin};
    for (int dz = -reach; dz <= reach; ++dz)
      for (int dx = -reach; dx <= reach; ++dx) {
        Vec3f q = copyOf(p, dx, dz).local;
        if (anyTriangleBoxMeets({q - m, q + m}, surface)) return {0u, false};
      }
    return {0u, true};
  }

  // Clear when, for every copy whose box comes near, no triangle's box comes within the margin
  // of [lo, hi] and the box's centre is outside that copy.
  GVDP_HD bool emptyBox(Vec3d lo, Vec3d hi, float voxelSize) const {
    double margin = EMPTY_MARGIN_VOXELS * static_cast<double>(voxelSize) + MESH_SLACK;
    Box3f bounds = surface.tree.bounds;
    int x0 = 0, x1 = 0, z0 = 0, z1 = 0;
    if (lattice != 0.0f) {
      double period = lattice;
      auto cell = [&](double a) { return static_cast<int>(floor(a / period + 0.5)); };
      x0 = cell(lo.x - margin - bounds.hi.x);
      x1 = cell(hi.x + margin - bounds.lo.x);
      z0 = cell(lo.z - margin - bounds.hi.z);
      z1 = cell(hi.z + margin - bounds.lo.z);
      if ((x1 - x0 + 1) * (z1 - z0 + 1) > MESH_BOX_CELLS) return false;
    }
    for (int cz = z0; cz <= z1; ++cz)
      for (int cx = x0; cx <= x1; ++cx) {
        Vec3d offset{cx * static_cast<double>(lattice), 0.0, cz * static_cast<double>(lattice)};
        Vec3d a = lo - offset - Vec3d{margin, margin, margin};
        Vec3d b = hi - offset + Vec3d{margin, margin, margin};
        if (anyTriangleBoxMeets({toFloat(a), toFloat(b)}, surface)) return false;
        Box3f box{toFloat(lo - offset), toFloat(hi - offset)};
        Vec3f centre = (box.lo + box.hi) * 0.5f;
        if (boxDistanceSq(centre, bounds) > 0.0f) continue;  // outside the copy's box
        if (insideByRay(centre, surface)) return false;
      }
    return true;
  }

  GVDP_HD float voxelSize0() const { return finest; }
};

static_assert(Producer<MeshWorld>);

// Where a mesh walk starts: before the model, looking at it (one model; the orbit goes around
// it), or in a corridor of the lattice, looking along +z.
inline CameraPose meshStart(float lattice) {
  if (lattice == 0.0f) return {{0.0, 0.08, -1.9}, 0.0f, -0.08f};
  return {{0.5 * lattice, 0.1, -0.5 * lattice}, 0.15f, -0.04f};
}

}  // namespace gvdp::detail
