// The reference a cached mesh frame is measured against (issue 15): each pixel's ray cast through
// the kd-tree to the first triangle of the copies it passes (world/mesh_world.h), shaded as a
// voxel there would be (the world's albedo, bakeShading at the interpolated vertex normal), fully
// opaque, within the clipmap's far distance; the sky elsewhere. No voxels, no LOD: what the
// volume approximates.
#pragma once

#include "gvdp/mesh/kdtree_raycast.h"
#include "gvdp/render/frame.h"
#include "gvdp/render/shade.h"
#include "gvdp/world/mesh_world.h"

namespace gvdp::detail {

GVDP_HD GVDP_INLINE Rgba8 meshReferencePixel(const FrameSetup& frame, const MeshWorld& world,
                                             int pixel) {
  Ray ray = frame.primaryRay(pixel % frame.width, pixel / frame.width);
  Vec3d origin = frame.localOrigin + toDouble(ray.o);
  float far = frame.lod.farDistance(), t = 0.0f;
  for (int guard = 0; guard < 1 << 16 && t < far; ++guard) {
    MeshCopy c = world.copyOf(origin + toDouble(ray.d * t));
    Vec3d offset{c.cx * static_cast<double>(world.lattice), 0.0,
                 c.cz * static_cast<double>(world.lattice)};
    Ray local{toFloat(origin - offset), ray.d};
    MeshHit hit = closestHit(local, world.surface.tree, world.surface.mesh);
    if (hit.triangle != KD_NO_HIT) {
      if (hit.t > far) break;
      const uint32_t* i = world.surface.mesh.indices + 3 * hit.triangle;
      const Vec3f* v = world.surface.mesh.vertices;
      NearestPoint at = nearestOnTriangle(local.o + local.d * hit.t, v[i[0]], v[i[1]], v[i[2]]);
      Vec3f colour = bakeShading(world.albedo(c.cx, c.cz),
                                 shadingNormal(world.surface, hit.triangle, at.b1, at.b2));
      return resolvePixel({colour.x, colour.y, colour.z, 1.0f}, ray.d);
    }
    if (world.lattice == 0.0f) break;
    // On to the next cell of the lattice along the ray (x and z; the copies keep to their cells).
    float half = 0.5f * world.lattice, exit = far;
    if (ray.d.x != 0.0f)
      exit = fminf(exit, ((ray.d.x > 0.0f ? half : -half) - local.o.x) / ray.d.x);
    if (ray.d.z != 0.0f)
      exit = fminf(exit, ((ray.d.z > 0.0f ? half : -half) - local.o.z) / ray.d.z);
    t = fmaxf(exit, t) + 1e-4f;  // exit: where the ray leaves the cell's column
  }
  return resolvePixel({0.0f, 0.0f, 0.0f, 0.0f}, ray.d);
}

}  // namespace gvdp::detail
