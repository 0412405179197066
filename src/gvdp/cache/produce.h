// The production task (paper Algorithm 2), written once for every cooperation scope
// (base/cooperation.h): one producer evaluation per sample of a brick, 10^3 samples = 8^3 voxels
// and a one-voxel border, at the voxel centres of the brick's level; the group ANDs the empty
// flags, takes a slot, writes the samples and publishes the entry (cache_ops.h). A CPU task runs
// it as a ThreadScope, sp/dp/graph's production kernels as a BlockScope, pt as a WarpScope whose
// samples idle warps of the block help compute (pt_kernels.cu: produceChunks, then commitBrick).
#pragma once

#include "gvdp/base/cooperation.h"
#include "gvdp/cache/brick_key.h"
#include "gvdp/cache/cache_ops.h"
#include "gvdp/render/brick_pool.h"
#include "gvdp/world/producer.h"

namespace gvdp::detail {

GVDP_HD GVDP_INLINE Vec3i brickSampleIndex(int sample) {
  return {sample % BRICK_SAMPLES, (sample / BRICK_SAMPLES) % BRICK_SAMPLES,
          sample / (BRICK_SAMPLES * BRICK_SAMPLES)};
}

// World position of a sample's voxel centre. Exact in double (voxel sizes are powers of two),
// hence equal to the direct renderer's localOrigin + (i + 1/2) v.
GVDP_HD GVDP_INLINE Vec3d brickSampleCentre(const BrickKey& key, int sample, float voxelSize0) {
  double vs = ldexp(static_cast<double>(voxelSize0), key.level);
  Vec3i i = brickSampleIndex(sample);
  auto centre = [&](int brick, int index) {
    long long voxel = static_cast<long long>(brick) * BRICK_WIDTH + index - 1;
    return (static_cast<double>(voxel) + 0.5) * vs;
  };
  return {centre(key.brick.x, i.x), centre(key.brick.y, i.y), centre(key.brick.z, i.z)};
}

template <class P>
GVDP_HD GVDP_INLINE VoxelSample produceBrickSample(const P& producer, const BrickKey& key,
                                                   int sample) {
  float vs = ldexpf(producer.voxelSize0(), key.level);
  return producer.voxel(brickSampleCentre(key, sample, producer.voxelSize0()), vs);
}

// The producer's emptiness bound for the box of the samples of the bricks key.brick + lo to
// key.brick + hi (offsets, inclusive), widened by one voxel (the reach of the empty-flag
// contract, world/producer.h), or its part `part` of `parts` (emptyBoxPart); the box's corners
// are the samples `first` of the first brick and `last` of the last. lo = hi = 0 and every sample:
// true makes the brick EMPTY unevaluated.
template <class P>
GVDP_HD GVDP_INLINE bool boxBoundedEmpty(const P& producer, const BrickKey& key, Vec3i lo, Vec3i hi,
                                         int part = 0, int parts = 1, int first = 0,
                                         int last = BRICK_SAMPLE_COUNT - 1) {
  double vs = ldexp(static_cast<double>(producer.voxelSize0()), key.level);
  Vec3d a = brickSampleCentre({key.brick + lo, key.level}, first, producer.voxelSize0());
  Vec3d b = brickSampleCentre({key.brick + hi, key.level}, last, producer.voxelSize0());
  return emptyBoxPartOf(producer, a - Vec3d{vs, vs, vs}, b + Vec3d{vs, vs, vs},
                        static_cast<float>(vs), part, parts);
}

template <class P>
GVDP_HD GVDP_INLINE bool brickBoundedEmpty(const P& producer, const BrickKey& key) {
  return boxBoundedEmpty(producer, key, {0, 0, 0}, {0, 0, 0});
}

// A group with BOX_PARTS members per bound tests each in BOX_PARTS parts at once, a member a part
// (world/producer.h: emptyBoxPart; the answer does not depend on the number): random-spheres'
// bound walks up to 125 cells a box, and its empty bricks' boxes (up to a hundred bounds each)
// kept 6 of sp's 512 threads busy (sp +13-16% with parts, H100). pt's warps thus test a brick's
// own bound in parts but the six faces' slabs whole: 5 parts a face gained nothing and cost
// perlin and forest 5-7% (BENCHMARKS.md).
constexpr int BOX_PARTS = 16;

// The parts of a bound tested at once by a group of `members` testing `tests` bounds.
GVDP_HD GVDP_INLINE int boxPartsFor(int members, int tests) {
  return members >= tests * BOX_PARTS ? BOX_PARTS : 1;
}

// The first and last samples of sub-box `box` of a brick's split x split x split: the split's
// ranges of the 10 samples per axis. Widened by one voxel as the whole box (boxBoundedEmpty), the
// sub-boxes cover the brick's box (neighbouring ranges' centres are one voxel apart), so every
// one clear implies what the whole box's bound would.
GVDP_HD GVDP_INLINE void subBoxSamples(int box, int split, int* first, int* last) {
  auto at = [&](int k) { return k * BRICK_SAMPLES / split; };
  Vec3i k{box % split, box / split % split, box / (split * split)};
  *first = at(k.x) + BRICK_SAMPLES * (at(k.y) + BRICK_SAMPLES * at(k.z));
  *last = at(k.x + 1) - 1 + BRICK_SAMPLES * (at(k.y + 1) - 1 + BRICK_SAMPLES * (at(k.z + 1) - 1));
}

// brickBoundedEmpty by a group, every member with the answer: EMPTY unevaluated when the whole
// box's bound clears it (in parts, a member each), or else every one of the producer's sub-boxes
// (boundSplit, world/producer.h; such a world's bound is one part), a member each. One call site
// of the bound (each inlines the world's whole bound into the kernels). In perlin's frame 12 most
// of the bricks produced were EMPTY, and a brick evaluated only to find it EMPTY costs its 1000
// samples against its sub-boxes' 27 bounds.
template <class Scope, class P>
GVDP_HD GVDP_INLINE bool brickBoundedEmpty(const Scope& group, const P& producer,
                                           const BrickKey& key) {
  const int split = boundSplitOf(producer), subBoxes = split > 1 ? split * split * split : 0;
  const int parts = subBoxes ? 1 : boxPartsFor(group.size(), 1);
  bool whole = true, sub = subBoxes > 0;
  for (int t = group.rank(); t < parts + subBoxes; t += group.size()) {
    int first = 0, last = BRICK_SAMPLE_COUNT - 1;
    if (t >= parts) {
      // A member that tested the whole box too (a one-thread group) stops where it decides.
      if (group.rank() < parts && whole) {
        sub = false;
        break;
      }
      if (!sub) break;
      subBoxSamples(t - parts, split, &first, &last);
    }
    bool clear = boxBoundedEmpty(producer, key, {0, 0, 0}, {0, 0, 0}, t < parts ? t : 0,
                                 t < parts ? parts : 1, first, last);
    if (t < parts)
      whole = whole && clear;
    else
      sub = sub && clear;
  }
  return group.all(whole) || (subBoxes > 0 && group.all(sub));
}

// The reach codes with `faces` (a bit per face) one step further: 0 to 1, then two codes
// (about twice the reach), up to `last`.
GVDP_HD GVDP_INLINE EmptyReachCodes grownCodes(EmptyReachCodes c, uint32_t faces, int last) {
  for (int f = 0; f < 6; ++f) {
    if (!(faces >> f & 1u)) continue;
    int next = c.face[f] == 0 ? 1 : c.face[f] + 2;
    c.face[f] = next < last ? next : last;
  }
  return c;
}

// The faces through which a ray from the eye leaves a brick (by its offset from the eye's brick
// of its level): along each axis, the face turned away from the eye, or both faces where the two
// bricks share the axis' slab. A box grows through these only: a ray leaves it through one of
// them, and growing the others would widen the slabs these add (a bound loosens with its box's
// diagonal) for no ray's benefit. The eye is the one of the frame that produces the brick; a box
// used after the eye moved to the other side of a face is left by that face at the brick's
// border (the ray then takes the next brick's box), never wrongly. Per face, the distance along
// its axis from the eye in bricks (at least 1/2): a ray's direction is about proportional to
// these, so the face it leaves a box by first is the one of least (reach + 1) / weight.
struct ExitFaces {
  uint32_t faces;  // a bit per face
  float weight[3];

  // Of `candidates` (a subset of faces), the face a ray from the eye leaves the box `codes` by
  // first (above), as a one-bit mask.
  GVDP_HD uint32_t firstLeft(const EmptyReachCodes& codes, uint32_t candidates) const {
    uint32_t best = 0u;
    float bestReach = 0.0f, bestWeight = 1.0f;
    for (int f = 0; f < 6; ++f) {
      if (!(candidates >> f & 1u)) continue;
      float reach = static_cast<float>(emptyReachOfCode(codes.face[f]) + 1);
      float w = weight[f % FACE_ABOVE];
      if (best == 0u || reach * bestWeight < bestReach * w) {
        best = 1u << f;
        bestReach = reach;
        bestWeight = w;
      }
    }
    return best;
  }
};

// The exit faces of brick `key` for the eye of the frame whose clipmap is `clipmap`.
GVDP_HD GVDP_INLINE ExitFaces exitFacesFrom(const Clipmap& clipmap, const BrickKey& key) {
  Vec3i offset = key.brick - clipmap.eyeBrick(key.level);
  ExitFaces e{0u, {}};
  for (int a = 0; a < FACE_ABOVE; ++a) {
    int d = a == 0 ? offset.x : a == 1 ? offset.y : offset.z;
    if (d <= 0) e.faces |= 1u << a;
    if (d >= 0) e.faces |= 1u << (a + FACE_ABOVE);
    e.weight[a] = static_cast<float>(d < 0 ? -d : d) + 0.5f;
  }
  return e;
}

// The box, in brick offsets from key.brick (lo, hi inclusive), of the slab that face f adds to
// a box: the bricks of `outer` beyond its reach through f in `inner` (the codes differ in that
// face only).
GVDP_HD GVDP_INLINE void slabOf(const EmptyReachCodes& inner, const EmptyReachCodes& outer,
                                int face, Vec3i& lo, Vec3i& hi) {
  EmptyReach in = emptyReach(emptyEntry(inner)), out = emptyReach(emptyEntry(outer));
  lo = {-out.below.x, -out.below.y, -out.below.z};
  hi = out.above;
  auto at = [](Vec3i& v, int axis) -> int& { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; };
  int axis = face % FACE_ABOVE;
  if (face < FACE_ABOVE)
    at(hi, axis) = -at(in.below, axis) - 1;
  else
    at(lo, axis) = at(in.above, axis) + 1;
}

// The EMPTY entry of an empty brick (brick_key.h: emptyEntry), by every member of the group,
// handed to publish(key, entry) (by every member too), which says whether the brick's parent is
// to be marked as well: if the producer's bound clears it, its entry is grown and handed over
// likewise, and so on up.
//
// A box grows in rounds from the brick (empty by its samples' flags or by the bound), through the
// faces rays from the eye leave it by (exitFacesFrom). In a round each face still growing tries
// its next reach (the slab it adds) and the faces the producer's bound clears grow together if
// the slabs they add to the box grown in all of them clear too, else the one a ray from the eye
// would leave the box by first alone; a face stops at its first refusal. In a block, each test
// is a face's bound in parts, a member a part (boxPartsFor). Testing only what a step adds keeps
// the bound's boxes small (a bound from the centre of a box loosens with its diagonal), so the
// box stretches along the empty directions: up and sideways above a terrain, along a cave.
//
// A group of GROW_AHEAD_MEMBERS or more tests more at once (in parallel members, so a round takes
// as long): beside each growing face's slab alone, the slabs of all growing faces grown together
// once and twice, and in a level's first round its parent's brick. A box that clears in all its
// growing faces thus grows two steps a round, and its parent is known when it is grown. A warp's
// growth took 11.4 rounds of 11-13 us each on average (perlin's walkthrough frame 12, H200,
// BENCHMARKS.md), the rays on the brick waiting for all of them; a single thread tests only what
// the step needs.
//
// One loop and one call of the producer's bound, which the compiler inlines with the whole
// world's bound: a test is the slab of one face (Alone), of a face of the faces grown together
// (Together, and ahead: once or twice), or a parent's brick (Parent, and ahead).
//
// The same growth makes boxes from the entries already known (table_boxes.h: growTableBox): a
// CLEAR brick's of bricks known zero at its level, an EMPTY brick's of bricks known empty, from
// the box the producer grew; neither climbs to the parent.
constexpr int GROW_TESTS = 6, GROW_AHEAD_TESTS = 3 * 6 + 1, GROW_AHEAD_MEMBERS = GROW_AHEAD_TESTS;

// The producer's emptiness bound as growBoxes tests it (boxBoundedEmpty): EMPTY boxes, which
// climb to the parent, grown ahead by a group wide enough.
template <class P>
struct ProducerBound {
  const P& producer;
  static constexpr bool CLIMBS = true;  // to the parent, grown ahead (table bounds: false)
  static constexpr int MAX_CODE = MAX_EMPTY_REACH_CODE;
  GVDP_HD EmptyReachCodes start() const { return {}; }  // from the brick alone
  GVDP_HD uint32_t entry(const EmptyReachCodes& c) const { return emptyEntry(c); }
  GVDP_HD int partsFor(int members, int tests) const { return boxPartsFor(members, tests); }
  GVDP_HD bool clear(const BrickKey& k, Vec3i lo, Vec3i hi, int part, int parts) const {
    return boxBoundedEmpty(producer, k, lo, hi, part, parts);
  }
};

template <class Scope, class Bound, class Publish>
GVDP_HD GVDP_INLINE void growBoxes(const Scope& group, const Bound& bound, BrickKey key,
                                   const Clipmap& clipmap, Publish&& publish) {
  enum class Step : uint8_t { Alone, Together, Parent };
  constexpr int PARENT_TEST = GROW_AHEAD_TESTS - 1;  // test bits: kind * 6 + face, then this
  const bool ahead = Bound::CLIMBS && group.size() >= GROW_AHEAD_MEMBERS;
  const int tests = ahead ? GROW_AHEAD_TESTS : GROW_TESTS;
  const int parts = bound.partsFor(group.size(), tests);
  auto growable = [&](uint32_t faces, const EmptyReachCodes& c) {
    uint32_t g = 0u;
    for (int f = 0; f < 6; ++f)
      if ((faces >> f & 1u) && c.face[f] < Bound::MAX_CODE) g |= 1u << f;
    return g;
  };
  Step step = Step::Alone;
  EmptyReachCodes codes = bound.start(), all{}, twice{};
  ExitFaces exits = exitFacesFrom(clipmap, key);
  uint32_t growing = growable(exits.faces, codes), cleared = 0u, again = 0u;  // a bit per face
  int parent = Bound::CLIMBS ? -1 : 0;  // its test's answer (-1: none yet)
  auto level = [&] {                    // the next brick's growth, from itself
    codes = {};
    exits = exitFacesFrom(clipmap, key);
    growing = exits.faces;
    parent = -1;
    step = Step::Alone;
  };
  for (;;) {
    if (step != Step::Parent && growing == 0u) {  // grown
      uint32_t entry = bound.entry(codes);
      if (!publish(key, entry) || parent == 0) return;
      key = {halfFloor(key.brick), key.level + 1};
      if (parent < 0) {
        step = Step::Parent;
      } else {
        level();
        continue;
      }
    }
    uint32_t tested = step == Step::Alone ? growing : step == Step::Together ? cleared : 1u;
    const bool several = (growing & (growing - 1u)) != 0u;
    if (ahead && step == Step::Alone) {
      all = grownCodes(codes, growing, Bound::MAX_CODE);
      again = growable(growing, all);
      twice = grownCodes(all, again, Bound::MAX_CODE);
      tested |= (several ? growing : 0u) << 6 | again << 12;
      if (parent < 0) tested |= 1u << PARENT_TEST;
    }
    uint32_t failed = 0u;
    for (int t = group.rank(); t < tests * parts; t += group.size()) {
      const int test = t / parts, f = test % 6, kind = test / 6;
      if (!(tested >> test & 1u)) continue;
      BrickKey k = key;
      Vec3i lo{0, 0, 0}, hi{0, 0, 0};
      if (test == PARENT_TEST) {
        k = {halfFloor(key.brick), key.level + 1};
      } else if (step != Step::Parent) {
        EmptyReachCodes outer = kind == 2 ? twice
                                : kind == 1 || step == Step::Together
                                    ? all
                                    : grownCodes(codes, 1u << f, Bound::MAX_CODE);
        EmptyReachCodes inner = outer;
        inner.face[f] = kind == 2 ? all.face[f] : codes.face[f];
        slabOf(inner, outer, f, lo, hi);
      }
      if (!bound.clear(k, lo, hi, t % parts, parts)) failed |= 1u << test;
    }
    const uint32_t passed = tested & ~group.any(failed);
    if (step == Step::Parent) {
      if (passed == 0u) return;
      level();
      continue;
    }
    if (tested >> PARENT_TEST & 1u) parent = static_cast<int>(passed >> PARENT_TEST & 1u);
    uint32_t take = 0u;
    if (step == Step::Together) {
      take = passed == cleared ? cleared : exits.firstLeft(codes, cleared);
      step = Step::Alone;
    } else {
      const uint32_t alone = passed & 63u;
      if (ahead && (several ? passed >> 6 & 63u : alone) == growing) {  // all together, once
        codes = all;
        growing = again;
        if (again != 0u && (passed >> 12 & 63u) == again) {  // and twice
          codes = twice;
          growing = growable(again, twice);
        }
        continue;
      }
      cleared = alone;
      if ((cleared & (cleared - 1u)) != 0u) {  // more than one face: all of them, or the first
        if (ahead && cleared == growing) {     // all of them were tested together above
          take = exits.firstLeft(codes, cleared);
        } else {
          all = grownCodes(codes, cleared, Bound::MAX_CODE);
          step = Step::Together;
          continue;
        }
      } else {
        take = cleared;
      }
    }
    codes = grownCodes(codes, take, Bound::MAX_CODE);
    growing = growable(cleared, codes);
  }
}

template <class Scope, class P, class Publish>
GVDP_HD GVDP_INLINE void growEmptyBoxes(const Scope& group, const P& producer, BrickKey key,
                                        const Clipmap& clipmap, Publish&& publish) {
  growBoxes(group, ProducerBound<P>{producer}, key, clipmap, publish);
}

// The box's members: the bricks of an EMPTY brick's box within BOX_MEMBER_REACH of it along each
// axis, each MISSING one marked EMPTY (one CAS each, so a claimed, produced or marked brick keeps
// its state) with the largest part of the box its own codes name. The bound cleared them with
// the box, so each is what its own production would find (EMPTY), without its climb; a ray that
// meets one from a side the brick's rays did not cross skips it at once instead of waiting for
// its production. Perlin's walkthrough had 85% of its productions EMPTY, most in boxes already
// grown (BENCHMARKS.md, session 53: reaches 1, 3, 5, 8, 16 measured, pt and sp FPS x1.10-1.21).
constexpr int BOX_MEMBER_REACH = 8;

template <class Scope>
GVDP_HD GVDP_INLINE void markBoxMembers(const Scope& group, const CacheView& cache,
                                        const BrickKey& key, uint32_t entry) {
  EmptyReach r = emptyReach(entry);
  auto lim = [](int v) { return v < BOX_MEMBER_REACH ? v : BOX_MEMBER_REACH; };
  Vec3i lo{-lim(r.below.x), -lim(r.below.y), -lim(r.below.z)};
  Vec3i hi{lim(r.above.x), lim(r.above.y), lim(r.above.z)};
  Vec3i n{hi.x - lo.x + 1, hi.y - lo.y + 1, hi.z - lo.z + 1};
  int count = n.x * n.y * n.z;
  if (count <= 1) return;
  uint32_t marked = 0u;
  for (int i = group.rank(); i < count; i += group.size()) {
    Vec3i o{lo.x + i % n.x, lo.y + i / n.x % n.y, lo.z + i / (n.x * n.y)};
    if (o.x == 0 && o.y == 0 && o.z == 0) continue;
    uint32_t index = cache.clipmap.windowEntry(key.level, key.brick + o);
    if (index == Clipmap::NOT_IN_WINDOW) continue;
    uint32_t member = emptyEntry(codesWithin({r.below + o, r.above - o}));
    if (loadRelaxed32(&cache.entries[index]) == ENTRY_MISSING &&
        atomicCas32(&cache.entries[index], ENTRY_MISSING, member) == ENTRY_MISSING)
      ++marked;
  }
  if (marked != 0u) atomicAdd32(&cache.counters[COUNTER_MARKED], marked);
}

// An empty brick is published EMPTY with the box the group grows for it, then its ancestors are
// marked EMPTY, each exactly as its own production would have found it, up to the first the
// producer's bound does not clear or that is not MISSING (claimed, produced or marked already:
// one CAS each, so a brick in production keeps its state and its claimant loses nothing). A ray
// that meets a missing brick under one skips it unproduced (cached_access.h). Before the brick's
// own entry, the members of its box are marked (markBoxMembers).
template <class Scope, class P>
GVDP_HD GVDP_INLINE void publishEmpty(const Scope& group, const P& producer, const CacheView& cache,
                                      BrickKey key) {
  uint32_t index = Clipmap::NOT_IN_WINDOW;  // of an ancestor
  growEmptyBoxes(group, producer, key, cache.clipmap, [&](const BrickKey& k, uint32_t entry) {
    uint32_t marked = 1u;
    if (index == Clipmap::NOT_IN_WINDOW) markBoxMembers(group, cache, k, entry);
    if (group.rank() == 0) {
      if (index == Clipmap::NOT_IN_WINDOW)
        publishBrick(cache, k, entry);
      else
        marked = atomicCas32(&cache.entries[index], ENTRY_MISSING, entry) == ENTRY_MISSING;
    }
    if (group.broadcast(marked) == 0u || k.level + 1 >= cache.clipmap.levels) return false;
    index = cache.clipmap.windowEntry(k.level + 1, halfFloor(k.brick));
    return index != Clipmap::NOT_IN_WINDOW;
  });
}

// An empty brick's entry before its box is grown (pt's GPU worker, which queues the brick's rays
// in between): the brick alone, as its own production found it. publishEmpty publishes it again
// with its box, and counts and lists it then.
GVDP_HD GVDP_INLINE void publishEmptyAlone(const CacheView& cache, const BrickKey& key) {
  storeRelease32(&cache.entries[cache.clipmap.entryIndex(key.level, key.brick)],
                 emptyEntry(EmptyReachCodes{}));
}

// Algorithm 2's end for a brick with matter, by a group whose member r holds the samples
// r + k * size (k < PER, with PER * size >= BRICK_SAMPLE_COUNT): the group ORs the occupancy
// cells of its nonzero samples staged(k, sample) (brick_pool.h); unless none is set (a CLEAR
// brick: no slot, nothing written, brick_key.h) the leader takes a slot, each member writes its
// samples to it and the leader the cells, each member fences (device scope: other blocks read the
// pool), and the leader publishes the entry once every member's writes are fenced.
template <int PER, class Scope, class Staged>
GVDP_HD GVDP_INLINE void commitSamples(const Scope& group, const CacheView& cache,
                                       const BrickPool& pool, const BrickKey& key, Staged staged) {
  uint64_t cells = 0;
  GVDP_UNROLL
  for (int k = 0; k < PER; ++k) {
    int s = group.rank() + k * group.size();
    if (s < BRICK_SAMPLE_COUNT && staged(k, s) != 0u)
      cells |= occupancyCellsOf(brickSampleIndex(s));
  }
  uint32_t low = group.any(static_cast<uint32_t>(cells));
  uint32_t high = group.any(static_cast<uint32_t>(cells >> 32));
  uint64_t occupancy = uint64_t{high} << 32 | low;
  if (occupancy == 0u) {
    if (group.rank() == 0) publishBrick(cache, key, ENTRY_CLEAR);
    return;
  }
  uint32_t slot = 0;
  if (group.rank() == 0) slot = takeFreeSlot(cache);
  slot = group.broadcast(slot);
  if (slot != MAX_SLOTS) {
    GVDP_UNROLL
    for (int k = 0; k < PER; ++k) {
      int s = group.rank() + k * group.size();
      if (s < BRICK_SAMPLE_COUNT) pool.write(slot, s, staged(k, s));
    }
    if (group.rank() == 0) pool.occupancy[slot] = occupancy;
#if GVDP_IS_GPU_CODE
    __threadfence();
#endif
  }
  group.sync();
  if (group.rank() == 0) publishBrick(cache, key, slot);
}

// Algorithm 2's end: an empty brick published by the group (publishEmpty), any other committed
// (commitSamples).
template <int PER, class Scope, class P, class Staged>
GVDP_HD GVDP_INLINE void commitBrick(const Scope& group, const P& producer, const CacheView& cache,
                                     const BrickPool& pool, const BrickKey& key, bool empty,
                                     Staged staged) {
  if (empty)
    publishEmpty(group, producer, cache, key);
  else
    commitSamples<PER>(group, cache, pool, key, staged);
}

// Algorithm 2 whole, by a group that keeps its samples in registers: member r evaluates the
// samples r + k * size (k < PER) unless the producer's box bound clears the brick, the group ANDs
// the empty flags and commits.
template <int PER, class Scope, class P>
GVDP_HD GVDP_INLINE void produceBrick(const Scope& group, const P& producer, const CacheView& cache,
                                      const BrickPool& pool, const BrickKey& key) {
  Rgba8 values[PER];
  bool bounded = brickBoundedEmpty(group, producer, key);
  bool empty = true;
  GVDP_UNROLL
  for (int k = 0; k < PER; ++k) {
    int s = group.rank() + k * group.size();
    values[k] = 0u;
    if (s < BRICK_SAMPLE_COUNT && !bounded) {
      VoxelSample v = produceBrickSample(producer, key, s);
      values[k] = v.rgba;
      empty = empty && v.empty;
    }
  }
  empty = group.all(empty);
  commitBrick<PER>(group, producer, cache, pool, key, empty, [&](int k, int) { return values[k]; });
}

}  // namespace gvdp::detail
