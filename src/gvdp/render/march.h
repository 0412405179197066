// The body of the rendering task (paper Algorithm 1), written once for every scheduler and both
// backends. A ray state is (accumulated colour, level, lattice step); the march samples one
// voxel per step at the cone's level, composites front to back and stops at opacity ~1.
// The Access policy answers, per brick, "resident (sample it)", "empty (skip it)" or "stop"
// (missing or in production: the caller saves the state and relaunches the ray later).
#pragma once

#include "gvdp/base/ray.h"
#include "gvdp/render/brick_pool.h"
#include "gvdp/render/empty_box.h"
#include "gvdp/render/lod.h"
#include "gvdp/render/trilinear.h"

namespace gvdp::detail {

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
// current sample, so a skip always progresses); `span` is the current level's.
GVDP_HD GVDP_INLINE void advanceTo(RayState& s, const Lod& lod, const LevelSpan& span, float t) {
  int level = s.level;
  if (t >= span.end) {
    ++level;
    while (level < lod.levels && t >= lod.levelEnd(level)) ++level;
    if (level >= lod.levels) {
      s.level = lod.levels;
      return;
    }
    s.level = level;
    s.step = lod.firstStepAtOrAfter(level, t);
    return;
  }
  int step = Lod::firstStepAtOrAfter(span, t);
  s.step = step <= s.step ? s.step + 1 : step;
}

enum class BrickState : uint8_t { Resident, StandIn, Empty, Stop, End };

// What to do with the brick under a sample: sample `slot` (Resident; its clear cells sample
// zero, `occupancy`) or leave the empty box `emptyCodes` names (render/empty_box.h; Empty),
// both at `level`, which is the sample's level or a coarser one (an EMPTY ancestor, or a
// resident ancestor). StandIn: a resident ancestor sampled for a brick that was not ready (a
// degraded frame, or past a frame's budget); it serves the samples of its whole box. End: past a
// frame's budget, nothing is resident to stand in: the ray ends with what it has composited.
struct BrickLookup {
  BrickState state;
  uint32_t slot;
  int level;
  Vec3i brick;                        // local brick coordinates at `level`
  uint64_t occupancy = ~uint64_t{0};  // Resident: the brick's occupied cells (brick_pool.h)
  uint32_t emptyCodes = 0;            // Empty: the box's reach codes
};

// The brick coordinate, along one axis, of the face through which a ray of direction component
// d leaves the empty box around `brick` (the far face of the last brick of the box).
GVDP_HD GVDP_INLINE int exitFaceAlong(int axis, int brick, float d, uint32_t emptyCodes) {
  return d >= 0.0f ? brick + emptyReachThrough(emptyCodes, axis + FACE_ABOVE) + 1
                   : brick - emptyReachThrough(emptyCodes, axis);
}

// Distance at which the ray leaves the box around `brick` that `emptyCodes` names (0: the brick
// alone), bricks `side` wide.
GVDP_HD GVDP_INLINE float boxExit(const Ray& ray, Vec3f invD, Vec3i brick, uint32_t emptyCodes,
                                  float side) {
  Vec3f exit{static_cast<float>(exitFaceAlong(0, brick.x, ray.d.x, emptyCodes)) * side,
             static_cast<float>(exitFaceAlong(1, brick.y, ray.d.y, emptyCodes)) * side,
             static_cast<float>(exitFaceAlong(2, brick.z, ray.d.z, emptyCodes)) * side};
  return planesExit(ray, invD, exit);
}

// v (a position in voxels of a level) from the origin of `brick` of that level: where the
// clear-brick test reads a position's occupancy cell (render/brick_pool.h: occupancyCellsBetween).
GVDP_HD GVDP_INLINE Vec3f voxelInBrick(Vec3f v, Vec3i brick) {
  return {v.x - static_cast<float>(brick.x * BRICK_WIDTH),
          v.y - static_cast<float>(brick.y * BRICK_WIDTH),
          v.z - static_cast<float>(brick.z * BRICK_WIDTH)};
}

// Paused: a warp's march broke off before this ray finished or stopped
// (render/march_warp.cuh, WarpMarchEnd::FirstStop); march() resumes it from its state.
enum class MarchResult : uint8_t { Finished, Stopped, Paused };

// Access provides:
//   BrickLookup lookup(int level, Vec3i brick)   brick: local brick coordinates at that level
//   Vec4f sample(const BrickLookup&, Vec3f p)    p: local position of the sample
// A resident lookup of the ray's level serves a run of samples (march, below). Otherwise a lookup
// is reused while the samples stay in its brick, a StandIn while they stay in its box (a coarser
// Resident one - the lookahead's prediction - is looked up again at every sample: the lookahead
// claims the finer bricks under it). Whether lookup r answers for brick `brick` of `level`:
GVDP_HD GVDP_INLINE bool covers(const BrickLookup& r, int level, Vec3i brick) {
  if (r.level == level) return brick == r.brick;
  int up = r.level - level;
  return r.state == BrickState::StandIn && up > 0 &&
         Vec3i{brick.x >> up, brick.y >> up, brick.z >> up} == r.brick;
}

// A ray's march as a sequence of steps, so that a warp can share the sampling of its lanes' rays
// (render/march_warp.cuh); march() below is its loop on one thread. seek() moves the state to
// the next sample that reads a brick, one brick decision at a time; the sample at s.step then
// reads `resident`, and so does every step up to runEnd (a run) without a seek.
template <class Access>
struct Marcher {
  enum class Seek : uint8_t { Due, Moved, Finished, Stopped };

  const Ray& ray;
  const Lod& lod;
  RayState& s;
  Access& access;
  BrickLookup resident{BrickState::Resident, 0u, -1, {0, 0, 0}};
  int spanLevel = -1;  // the level `span` describes
  // The run: steps up to runEnd of spanLevel lie in `resident`'s brick (a resident brick of their
  // level, from its entry to where the ray leaves it or the level) and sample it with no brick
  // test. A sample of the run on a face may round into the neighbour: the brick gives it the
  // neighbour's value (the shared border; an EMPTY neighbour's bound reaches a voxel into it).
  int runEnd = -1;
  LevelSpan span{};
  Vec3f invD;

  GVDP_HD Marcher(const Ray& r, const Lod& l, RayState& state, Access& a)
      : ray(r), lod(l), s(state), access(a), invD(inverseDirection(r)) {}

  // Due: the sample at s.step reads `resident`. Moved: the state moved on without a sample (a
  // level's end, an EMPTY box, a clear brick); seek again. Finished, Stopped: as march().
  GVDP_HD Seek seek() {
    if (s.finished(lod)) return Seek::Finished;
    if (s.level != spanLevel) {
      span = lod.span(s.level);
      spanLevel = s.level;
      runEnd = -1;
    }
    if (s.step <= runEnd) return Seek::Due;
    float t = span.sampleT(s.step);
    if (t >= span.end) {
      ++s.level;
      s.step = 0;
      return Seek::Moved;
    }
    // A position on a brick face may round to either brick: both give it the same value (above).
    Vec3f p = ray.o + ray.d * t;
    Vec3i brick = span.brickOf(p);
    if (covers(resident, s.level, brick)) return Seek::Due;
    BrickLookup b = access.lookup(s.level, brick);
    if (b.state == BrickState::Stop) return Seek::Stopped;
    if (b.state == BrickState::End) {
      s.level = lod.levels;
      return Seek::Finished;
    }
    if (b.state == BrickState::Empty) {
      // Every sample of the box at a level up to the box's own is zero (a CLEAR box, which
      // comes only at the ray's level: at that level); coarser samples in it may not be: the
      // skip ends at the box or at the end of its level, whichever comes first. A sample is thus
      // skipped exactly when it is zero-valued by an EMPTY box of its level or a coarser one or a
      // CLEAR box of its level, whichever boxes the lookups happened to return: the image does
      // not depend on how far each skip goes.
      bool own = b.level == s.level;
      float side = (own ? span.voxelSize : lod.voxelSize(b.level)) * BRICK_WIDTH;
      float levelEnd = own ? span.end : lod.levelEnd(b.level);
      advanceTo(s, lod, span, fminf(boxExit(ray, invD, b.brick, b.emptyCodes, side), levelEnd));
      return Seek::Moved;
    }
    resident = b;
    // A brick of the ray's level whose samples from here to where the ray leaves it (or the
    // level) all lie in clear cells is left at once: each of them samples zero. The cells of the
    // first and the last sample bound those of the ones between (positions and cells are
    // monotone along the ray), so the test is exact. Otherwise its samples are a run.
    if (b.state == BrickState::Resident && b.level == s.level) {
      float tEnd = fminf(boxExit(ray, invD, b.brick, 0u, span.voxelSize * BRICK_WIDTH), span.end);
      int last = Lod::firstStepAtOrAfter(span, tEnd) - 1;
      if (last > s.step) {
        Vec3f q = ray.o + ray.d * span.sampleT(last);
        if (!(b.occupancy & occupancyCellsBetween(voxelInBrick(span.inVoxels(p), b.brick),
                                                  voxelInBrick(span.inVoxels(q), b.brick)))) {
          advanceTo(s, lod, span, tEnd);
          return Seek::Moved;
        }
      }
      runEnd = last;
    }
    return Seek::Due;
  }

  // The samples from s.step that read `resident` without a seek (Due: at least 1).
  GVDP_HD int runLength() const { return (runEnd > s.step ? runEnd : s.step) - s.step + 1; }

  // The position of the sample at s.step.
  GVDP_HD Vec3f position() const { return ray.o + ray.d * span.sampleT(s.step); }

  // Composites the sample at s.step (front to back) and steps on.
  GVDP_HD void composite(Vec4f c) {
    float k = 1.0f - s.colour.w;
    s.colour = {s.colour.x + k * c.x, s.colour.y + k * c.y, s.colour.z + k * c.z,
                s.colour.w + k * c.w};
    ++s.step;
  }
};

template <class Access>
GVDP_HD MarchResult march(const Ray& ray, const Lod& lod, RayState& s, Access& access) {
  using Seek = typename Marcher<Access>::Seek;
  Marcher<Access> m(ray, lod, s, access);
  for (;;) {
    Seek k = m.seek();
    if (k == Seek::Moved) continue;
    if (k == Seek::Finished) return MarchResult::Finished;
    if (k == Seek::Stopped) return MarchResult::Stopped;
    m.composite(access.sample(m.resident, m.position()));
  }
}

}  // namespace gvdp::detail
