// The closed set of built-in scenes, dispatched by tag (docs/STYLE.md 4: no virtual calls in device
// code). A producer is a deterministic function (world position of a voxel centre, voxel size)
// -> VoxelSample; CPU and GPU evaluate the very same code.
#pragma once

#include <cstdint>

#include "gvdp/world/forest.h"
#include "gvdp/world/spheres.h"
#include "gvdp/world/terrain.h"

namespace gvdp {

enum class SceneKind : uint8_t { Perlin, Fbm, Forest, RandomSpheres, AlignedSpheres };
constexpr int SCENE_COUNT = 5;

struct SceneParams {
  SceneKind kind;
  float voxelSize0;  // voxel size at level 0, in world units
  uint32_t seed;
};

GVDP_HD GVDP_INLINE VoxelSample produceVoxel(const SceneParams& scene, Vec3d p, float voxelSize) {
  switch (scene.kind) {
    case SceneKind::Perlin:
      return producePerlin(p, voxelSize, scene.seed);
    case SceneKind::Fbm:
      return produceFbm(p, voxelSize, scene.seed);
    case SceneKind::Forest:
      return produceForest(p, voxelSize, scene.seed);
    case SceneKind::RandomSpheres:
      return produceRandomSpheres(p, voxelSize, scene.seed);
    default:
      return produceAlignedSpheres(p, voxelSize, scene.seed);
  }
}

}  // namespace gvdp
