// The body of the rendering task (paper Algorithm 1), written once for every scheduler and both
// backends. A ray state is (accumulated colour, level, lattice step); the march samples one
// voxel per step at the cone's level, composites front to back and stops at opacity ~1.
// The Access policy answers, per brick, "resident (sample it)", "empty (skip it)" or "stop"
// (missing or in production: the caller saves the state and relaunches the ray later).
#pragma once

#include "gvdp/base/ray.h"
#include "gvdp/render/lod.h"
#include "gvdp/render/trilinear.h"

namespace gvdp {

constexpr float OPAQUE_ALPHA = 0.99f;

struct RayState {
  Vec4f colour;  // premultiplied, front to back
  int level;     // == lod.levels once the ray has left the last level
  int step;      // lattice step within the level

  GVDP_HD bool finished(const Lod& lod) const {
    return colour.w >= OPAQUE_ALPHA || level >= lod.levels;
  }
};

GVDP_HD GVDP_INLINE RayState initialRayState() {
  return {{0, 0, 0, 0}, 0, 0};
}

// Moves the state to the first lattice sample at or after distance t (strictly after the
// current sample, so a skip always progresses).
GVDP_HD GVDP_INLINE void advanceTo(RayState& s, const Lod& lod, float t) {
  int level = s.level;
  while (level < lod.levels && t >= lod.levelEnd(level)) ++level;
  if (level >= lod.levels) {
    s.level = lod.levels;
    return;
  }
  int step = lod.firstStepAtOrAfter(level, t);
  if (level == s.level && step <= s.step) step = s.step + 1;
  s.level = level;
  s.step = step;
}

enum class BrickState : uint8_t { Resident, Empty, Stop };

struct BrickLookup {
  BrickState state;
  uint32_t slot;  // when Resident
};

enum class MarchResult : uint8_t { Finished, Stopped };

// Access provides:
//   BrickLookup lookup(int level, Vec3i brick)    brick: local brick coordinates at that level
//   Vec4f sample(int level, Vec3i brick, const BrickLookup&, Vec3f v)   v: local voxel coords
template <class Access>
GVDP_HD MarchResult march(const Ray& ray, const Lod& lod, RayState& s, Access& access) {
  while (!s.finished(lod)) {
    float t = lod.sampleT(s.level, s.step);
    if (t >= lod.levelEnd(s.level)) {
      ++s.level;
      s.step = 0;
      continue;
    }
    float vs = lod.voxelSize(s.level);
    Vec3f p = ray.o + ray.d * t;
    Vec3f v = p / vs;
    Vec3i brick = floorToInt(v * (1.0f / BRICK_WIDTH));
    BrickLookup b = access.lookup(s.level, brick);
    if (b.state == BrickState::Stop) return MarchResult::Stopped;
    if (b.state == BrickState::Empty) {
      float side = vs * BRICK_WIDTH;
      Vec3f lo{brick.x * side, brick.y * side, brick.z * side};
      advanceTo(s, lod, boxExit(ray, lo, lo + Vec3f{side, side, side}));
      continue;
    }
    Vec4f c = access.sample(s.level, brick, b, v);
    float k = 1.0f - s.colour.w;
    s.colour = {s.colour.x + k * c.x, s.colour.y + k * c.y, s.colour.z + k * c.z,
                s.colour.w + k * c.w};
    ++s.step;
  }
  return MarchResult::Finished;
}

}  // namespace gvdp
