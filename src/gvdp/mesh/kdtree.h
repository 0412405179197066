// The full-SAH kd-tree over a mesh's triangles: its node layout, its cost constants and the rules
// every builder applies (Wald and Havran 2006, "On building fast kd-trees for ray tracing, and on
// doing that in O(N log N)"; the GPU construction of seed 004, section 11.2). The rules are
// GVDP_HD functions over PODs, written in box.h's explicitly rounded arithmetic, so a builder on
// the GPU (level by level, as the seed) makes the same decision for a node as the sequential one
// and the two trees are equal node for node (sameTree, kdtree_stats.h).
//
// Rules (docs/DESIGN.md "Meshes"):
// - No clipping: a triangle is its bounding box. Per axis a triangle gives a START event at its
//   box's minimum and an END event at its maximum, or one PLANAR event when it is flat on that
//   axis (minimum == maximum). Events are ordered by (position, END < PLANAR < START, triangle).
// - A candidate plane is a distinct event position p strictly inside the node's box on that axis.
//   Counts: left = #{min < p} + #{flat at p}, right = #{max > p} (the seed: flat triangles in the
//   plane count on the left).
// - Cost: TRAVERSAL + INTERSECTION * (A(left) * left + A(right) * right) / A(node), A half the
//   surface area; the best split has the lowest cost, then the lowest axis (x < y < z), then the
//   lowest position. A node is a leaf when it holds at most MAX_LEAF_TRIANGLES, is at MAX_DEPTH,
//   has no candidate, or its best cost is not below INTERSECTION * triangles.
// - Assignment: left = {min < p} and right = {max > p}, plus the triangles flat at p to BOTH.
#pragma once

#include <bit>
#include <cstdint>
#include <limits>

#include "gvdp/base/defs.h"
#include "gvdp/mesh/box.h"

namespace gvdp::detail {

constexpr float KD_COST_TRAVERSAL = 15.0f;
constexpr float KD_COST_INTERSECTION = 20.0f;
constexpr uint32_t KD_MAX_LEAF_TRIANGLES = 2;  // a node of at most this many is a leaf
constexpr int KD_MAX_DEPTH = 48;               // the root is depth 0
constexpr int KD_STACK_SIZE = KD_MAX_DEPTH + 2;
constexpr uint32_t KD_MAX_INDEX = (1u << 30) - 1;  // first child or first leaf triangle

// --- nodes -----------------------------------------------------------------------------------
// 8 bytes. Interior: axis 0..2 and the index of its left child (the right one follows it) and
// the split position. Leaf: axis field 3, the first of its triangles in the tree's leaf
// triangle list (ascending triangle ids) and their count. The root is node 0; no other order is
// implied, so builders may store nodes as they like (depth first, level by level).
struct KdNode {
  uint32_t word;     // bits 0-1: axis, 3 for a leaf; bits 2-31: first child or first triangle
  uint32_t payload;  // interior: the split position's bits; leaf: the triangle count
};
constexpr uint32_t KD_LEAF = 3;

GVDP_HD GVDP_INLINE uint32_t floatBits(float f) {
#if GVDP_IS_GPU_CODE
  return __float_as_uint(f);
#else
  return std::bit_cast<uint32_t>(f);
#endif
}
GVDP_HD GVDP_INLINE float bitsFloat(uint32_t u) {
#if GVDP_IS_GPU_CODE
  return __uint_as_float(u);
#else
  return std::bit_cast<float>(u);
#endif
}

GVDP_HD GVDP_INLINE KdNode kdInterior(int axis, float split, uint32_t firstChild) {
  return {firstChild << 2 | static_cast<uint32_t>(axis), floatBits(split)};
}
GVDP_HD GVDP_INLINE KdNode kdLeaf(uint32_t firstTriangle, uint32_t count) {
  return {firstTriangle << 2 | KD_LEAF, count};
}
GVDP_HD GVDP_INLINE bool isLeaf(KdNode n) {
  return (n.word & 3u) == KD_LEAF;
}
GVDP_HD GVDP_INLINE int splitAxis(KdNode n) {
  return static_cast<int>(n.word & 3u);
}
GVDP_HD GVDP_INLINE float splitPosition(KdNode n) {
  return bitsFloat(n.payload);
}
GVDP_HD GVDP_INLINE uint32_t leftChild(KdNode n) {
  return n.word >> 2;
}
GVDP_HD GVDP_INLINE uint32_t rightChild(KdNode n) {
  return (n.word >> 2) + 1;
}
GVDP_HD GVDP_INLINE uint32_t leafFirst(KdNode n) {
  return n.word >> 2;
}
GVDP_HD GVDP_INLINE uint32_t leafCount(KdNode n) {
  return n.payload;
}

// A tree in memory it does not own (host vectors or device buffers).
struct KdTreeView {
  const KdNode* nodes;
  const uint32_t* leafTriangles;
  Box3f bounds;  // the root's box: the union of the triangles' boxes
};

// The two children's boxes of a split.
GVDP_HD GVDP_INLINE Box3f leftBox(Box3f b, int axis, float p) {
  setComponent(b.hi, axis, p);
  return b;
}
GVDP_HD GVDP_INLINE Box3f rightBox(Box3f b, int axis, float p) {
  setComponent(b.lo, axis, p);
  return b;
}

// --- events ----------------------------------------------------------------------------------
constexpr uint32_t KD_EVENT_END = 0;
constexpr uint32_t KD_EVENT_PLANAR = 1;
constexpr uint32_t KD_EVENT_START = 2;

struct KdEvent {
  float pos;
  uint32_t triangleAndType;  // triangle << 2 | type
};
GVDP_HD GVDP_INLINE KdEvent kdEvent(float pos, uint32_t triangle, uint32_t type) {
  return {canonicalZero(pos), triangle << 2 | type};
}
GVDP_HD GVDP_INLINE uint32_t eventTriangle(KdEvent e) {
  return e.triangleAndType >> 2;
}
GVDP_HD GVDP_INLINE uint32_t eventType(KdEvent e) {
  return e.triangleAndType & 3u;
}
// Float bits as an unsigned integer of the same order (positions are finite, -0 made +0).
GVDP_HD GVDP_INLINE uint32_t orderedBits(float f) {
  uint32_t u = floatBits(f);
  return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}
// The sort key of (position, type): a stable radix sort of events made in triangle order on
// this key gives kdEventLess's order (the GPU's way); the CPU sorts with kdEventLess.
GVDP_HD GVDP_INLINE uint64_t eventKey(KdEvent e) {
  return uint64_t{orderedBits(e.pos)} << 2 | eventType(e);
}
GVDP_HD GVDP_INLINE bool kdEventLess(KdEvent a, KdEvent b) {
  uint64_t ka = eventKey(a), kb = eventKey(b);
  return ka < kb || (ka == kb && eventTriangle(a) < eventTriangle(b));
}

// A triangle's box, its bounds made canonical (every builder starts from these).
GVDP_HD GVDP_INLINE Box3f kdTriangleBox(Vec3f a, Vec3f b, Vec3f c) {
  Box3f box = triangleBox(a, b, c);
  return {{canonicalZero(box.lo.x), canonicalZero(box.lo.y), canonicalZero(box.lo.z)},
          {canonicalZero(box.hi.x), canonicalZero(box.hi.y), canonicalZero(box.hi.z)}};
}

// --- the SAH -----------------------------------------------------------------------------------
struct KdSplit {
  float cost;  // +infinity: none
  int axis;    // -1: none
  float pos;
  uint32_t left, right;  // SAH counts (flat triangles in the plane on the left)
};
GVDP_HD GVDP_INLINE KdSplit noSplit() {
  return {std::numeric_limits<float>::infinity(), -1, 0.0f, 0, 0};
}

// Cost of splitting `box` at `pos` on `axis` with these counts; A(box) > 0.
GVDP_HD GVDP_INLINE float sahSplitCost(Box3f box, int axis, float pos, uint32_t left,
                                       uint32_t right) {
  float weighted =
      roundedAdd(roundedMul(halfArea(leftBox(box, axis, pos)), static_cast<float>(left)),
                 roundedMul(halfArea(rightBox(box, axis, pos)), static_cast<float>(right)));
  return roundedAdd(KD_COST_TRAVERSAL,
                    roundedMul(KD_COST_INTERSECTION, roundedDiv(weighted, halfArea(box))));
}
GVDP_HD GVDP_INLINE float sahLeafCost(uint32_t triangles) {
  return roundedMul(KD_COST_INTERSECTION, static_cast<float>(triangles));
}

// Is `pos` a candidate plane of `box` on `axis`?
GVDP_HD GVDP_INLINE bool isCandidate(Box3f box, int axis, float pos) {
  return component(box.lo, axis) < pos && pos < component(box.hi, axis);
}

// The order of splits: lower cost, then lower axis, then lower position. A total order on the
// candidates of one node (positions are distinct per axis), so any reduction finds the same one.
GVDP_HD GVDP_INLINE bool betterSplit(const KdSplit& a, const KdSplit& b) {
  if (a.cost != b.cost) return a.cost < b.cost;
  if (a.axis != b.axis) return static_cast<unsigned>(a.axis) < static_cast<unsigned>(b.axis);
  return a.pos < b.pos;
}

// The candidate `pos` of a node, evaluated; noSplit() when `pos` is not a candidate.
GVDP_HD GVDP_INLINE KdSplit evaluateSplit(Box3f box, int axis, float pos, uint32_t left,
                                          uint32_t right) {
  if (!isCandidate(box, axis, pos)) return noSplit();
  return {sahSplitCost(box, axis, pos, left, right), axis, pos, left, right};
}

// The leaf rule: does a node of `triangles` at `depth` with this best split become interior?
GVDP_HD GVDP_INLINE bool shouldSplit(Box3f box, uint32_t triangles, int depth,
                                     const KdSplit& best) {
  return triangles > KD_MAX_LEAF_TRIANGLES && depth < KD_MAX_DEPTH && halfArea(box) > 0.0f &&
         best.axis >= 0 && best.cost < sahLeafCost(triangles);
}

// The sweep as a per-event rule (the level-by-level builder's; the sequential sweep visits the
// same planes with the same counts). `before` counts the START, PLANAR and END events of the
// node's list before event i (an exclusive scan). A position p is evaluated once: at its first
// START event with the counts before it, or, where p has no START, at its last event with the
// counts including it; either way the ENDs and PLANARs at p are counted and the STARTs at p not,
// so left = STARTs before p + PLANARs up to p, right = n - ENDs and PLANARs up to p.
struct KdEventCounts {
  uint32_t start, planar, end;
};
GVDP_HD GVDP_INLINE KdEventCounts operator+(KdEventCounts a, KdEventCounts b) {
  return {a.start + b.start, a.planar + b.planar, a.end + b.end};
}
GVDP_HD GVDP_INLINE KdEventCounts operator-(KdEventCounts a, KdEventCounts b) {
  return {a.start - b.start, a.planar - b.planar, a.end - b.end};
}
GVDP_HD GVDP_INLINE KdEventCounts countsOf(KdEvent e) {
  uint32_t t = eventType(e);
  return {t == KD_EVENT_START ? 1u : 0u, t == KD_EVENT_PLANAR ? 1u : 0u,
          t == KD_EVENT_END ? 1u : 0u};
}
// Events [begin, end) of one node on `axis`, sorted; i in it; n the node's triangles.
GVDP_HD GVDP_INLINE KdSplit evaluateEvent(const KdEvent* ev, uint32_t i, uint32_t begin,
                                          uint32_t end, KdEventCounts before, uint32_t n, Box3f box,
                                          int axis) {
  KdEvent e = ev[i];
  if (eventType(e) == KD_EVENT_START) {
    bool firstStart =
        i == begin || ev[i - 1].pos != e.pos || eventType(ev[i - 1]) != KD_EVENT_START;
    if (!firstStart) return noSplit();
  } else {
    bool lastOfPosition = i + 1 == end || ev[i + 1].pos != e.pos;
    if (!lastOfPosition) return noSplit();
    before = before + countsOf(e);
  }
  return evaluateSplit(box, axis, e.pos, before.start + before.planar,
                       n - before.end - before.planar);
}

// Where an event's triangle goes for the split (axis, p), event on that axis: bit 0 left,
// bit 1 right; a triangle's sides are the OR over its events (its START says left when min < p,
// its END says right when max > p; a PLANAR event both at once). The seed's per-event rule.
constexpr uint32_t KD_LEFT = 1, KD_RIGHT = 2;
GVDP_HD GVDP_INLINE uint32_t eventSides(KdEvent e, float p) {
  uint32_t type = eventType(e);
  if (type == KD_EVENT_START) return e.pos < p ? KD_LEFT : 0u;
  if (type == KD_EVENT_END) return e.pos > p ? KD_RIGHT : 0u;
  return e.pos < p ? KD_LEFT : (e.pos > p ? KD_RIGHT : KD_LEFT | KD_RIGHT);
}

}  // namespace gvdp::detail
