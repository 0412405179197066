#include "gvdp/world/registry.h"

#include <array>

#include "gvdp/base/error.h"

namespace gvdp::detail {
namespace {

// Height of the first matter below `top` at (x, z), at the finest voxel size.
double surfaceHeight(const BuiltinScene& scene, double x, double z, double top) {
  for (double y = top; y > top - 400.0; y -= 0.25)
    if ((scene.voxel({x, y, z}, scene.voxelSize0()).rgba >> 24) != 0) return y;
  return top - 400.0;
}

std::array<SceneInfo, SCENE_COUNT> makeScenes() {
  std::array<SceneInfo, SCENE_COUNT> s{{
      {"perlin",
       "two layers of 3D Perlin noise: cliffs, arches and caves (costly producer)",
       {SceneKind::Perlin, 1.0f / 16.0f, 1u},
       {{10.5, 0.0, 0.5}, 0.3f, -0.12f},
       0.35f},
      {"fbm",
       "up to 10 octaves of 3D noise, octaves adapted to the LOD: detail near, world far",
       {SceneKind::Fbm, 1.0f / 16.0f, 3u},
       {{0.5, 0.0, 0.5}, 0.8f, -0.18f},
       0.6f},
      {"forest",
       "trees with see-through foliage: 16 leaf SDFs with sin-hash randoms per voxel",
       {SceneKind::Forest, 1.0f / 32.0f, 5u},
       {{0.3, 0.0, 0.3}, 0.6f, 0.06f},
       0.25f},
      {"random-spheres",
       "randomly placed spheres in 3D: uncorrelated disocclusion",
       {SceneKind::RandomSpheres, 1.0f / 16.0f, 9u},
       {{1.1, 2.3, 0.7}, 0.5f, 0.1f},
       0.3f},
      {"aligned-spheres",
       "spheres on a grid: free sight to the horizon, synchronised disocclusion",
       {SceneKind::AlignedSpheres, 1.0f / 16.0f, 0u},
       {{0.9, 0.9, 0.4}, 0.3f, 0.0f},
       0.3f},
  }};
  // Terrain-like scenes: put the eye a little above the ground under the start position.
  s[0].start.position.y = surfaceHeight(s[0].world, 10.5, 0.5, 40.0) + 5.0;
  s[1].start.position.y = surfaceHeight(s[1].world, 0.5, 0.5, 200.0) + 10.0;
  s[2].start.position.y = surfaceHeight(s[2].world, 0.3, 0.3, 3.0) + 1.7;
  return s;
}

}  // namespace

std::span<const SceneInfo> allScenes() {
  static const std::array<SceneInfo, SCENE_COUNT> scenes = makeScenes();
  return scenes;
}

std::string sceneNames() {
  std::string names;
  for (const SceneInfo& s : allScenes()) names += (names.empty() ? "" : ", ") + std::string(s.name);
  return names;
}

const SceneInfo& findScene(std::string_view name) {
  for (const SceneInfo& s : allScenes())
    if (s.name == name) return s;
  throw InputError("unknown scene '" + std::string(name) + "' (scenes: " + sceneNames() + ")");
}

}  // namespace gvdp::detail
