// The five built-in worlds as producers (world/producer.h), each a type of its own, and
// BuiltinScene, one of the five chosen by tag (docs/STYLE.md 4: no virtual calls in device
// code), whose visit gives the library each world's own kernels (sched/builtin_producer.cpp).
// perlin and fbm bound boxes by their gradients and curvature (terrain.h), forest by the height of
// its trees and the distances of its cells' trees and ground, random-spheres by the spheres of the
// cells a box overlaps, aligned-spheres by the lattice's sphere nearest the box.
#pragma once

#include <cstdint>
#include <type_traits>

#include "gvdp/world/forest.h"
#include "gvdp/world/producer.h"
#include "gvdp/world/spheres.h"
#include "gvdp/world/terrain.h"

namespace gvdp::detail {

GVDP_HD GVDP_INLINE bool noBoxBound(Vec3d, Vec3d, float, uint32_t) {
  return false;
}

// A world's bound in one part: part 0 is the whole (world/producer.h: emptyBoxPart).
struct BoundInOnePart {};

// random-spheres' bound in parts (world/spheres.h).
struct RandomSpheresBoundParts {
  GVDP_HD static bool emptyBoxPart(Vec3d lo, Vec3d hi, float voxelSize, uint32_t seed, int part,
                                   int parts) {
    return randomSpheresEmptyBoxPart(lo, hi, voxelSize, seed, part, parts);
  }
};

// A built-in world: a producer function of (position, voxel size, seed) at a level-0 voxel size,
// its box bound, how the bound splits into parts (a type: a comparison of function pointers
// is no constant expression under GCC's -fsanitize=undefined) and into sub-boxes (boundSplit,
// world/producer.h).
template <VoxelSample (*FN)(Vec3d, float, uint32_t),
          bool (*EMPTY_BOX)(Vec3d, Vec3d, float, uint32_t) = noBoxBound,
          class PARTS = BoundInOnePart, int SPLIT = 1>
struct SeededWorld {
  float finest;
  uint32_t seed;

  GVDP_HD VoxelSample voxel(Vec3d p, float voxelSize) const { return FN(p, voxelSize, seed); }
  GVDP_HD bool emptyBox(Vec3d lo, Vec3d hi, float voxelSize) const {
    return EMPTY_BOX(lo, hi, voxelSize, seed);
  }
  GVDP_HD bool emptyBoxPart(Vec3d lo, Vec3d hi, float voxelSize, int part, int parts) const {
    if constexpr (std::is_same_v<PARTS, BoundInOnePart>)
      return part != 0 || EMPTY_BOX(lo, hi, voxelSize, seed);
    else
      return PARTS::emptyBoxPart(lo, hi, voxelSize, seed, part, parts);
  }
  GVDP_HD int boundSplit() const { return SPLIT; }
  GVDP_HD float voxelSize0() const { return finest; }
};

// The sphere worlds' bounds are distances to their spheres: sub-boxes clear none of the bricks
// they leave (measured over every brick of x and z 0-24, y -40 to 40, levels 0-3).
using PerlinWorld = SeededWorld<producePerlin, perlinEmptyBox, BoundInOnePart, 3>;
using FbmWorld = SeededWorld<produceFbm, fbmEmptyBox, BoundInOnePart, 3>;
using ForestWorld = SeededWorld<produceForest, forestEmptyBox, BoundInOnePart, 3>;
using RandomSpheresWorld =
    SeededWorld<produceRandomSpheres, randomSpheresEmptyBox, RandomSpheresBoundParts>;
using AlignedSpheresWorld = SeededWorld<produceAlignedSpheres, alignedSpheresEmptyBox>;

enum class SceneKind : uint8_t { Perlin, Fbm, Forest, RandomSpheres, AlignedSpheres };
constexpr int SCENE_COUNT = 5;

struct BuiltinScene {
  SceneKind kind;
  float finest;  // voxel size at level 0, in world units
  uint32_t seed;

  // Calls f with the chosen world (the one switch over the kinds). Host code calls it with
  // host-only functors too (sched/builtin_producer.cpp: each world's kernels).
  GVDP_HD_CALLS_FUNCTOR
  template <class F>
  GVDP_HD auto visit(F f) const {
    switch (kind) {
      case SceneKind::Perlin:
        return f(PerlinWorld{finest, seed});
      case SceneKind::Fbm:
        return f(FbmWorld{finest, seed});
      case SceneKind::Forest:
        return f(ForestWorld{finest, seed});
      case SceneKind::RandomSpheres:
        return f(RandomSpheresWorld{finest, seed});
      default:
        return f(AlignedSpheresWorld{finest, seed});
    }
  }
  GVDP_HD VoxelSample voxel(Vec3d p, float voxelSize) const {
    return visit([&](const auto& world) { return world.voxel(p, voxelSize); });
  }
  GVDP_HD bool emptyBox(Vec3d lo, Vec3d hi, float voxelSize) const {
    return visit([&](const auto& world) { return world.emptyBox(lo, hi, voxelSize); });
  }
  GVDP_HD bool emptyBoxPart(Vec3d lo, Vec3d hi, float voxelSize, int part, int parts) const {
    return visit(
        [&](const auto& world) { return world.emptyBoxPart(lo, hi, voxelSize, part, parts); });
  }
  GVDP_HD int boundSplit() const {
    return visit([](const auto& world) { return world.boundSplit(); });
  }
  GVDP_HD float voxelSize0() const { return finest; }
};

static_assert(Producer<BuiltinScene> && Producer<PerlinWorld>);

}  // namespace gvdp::detail
