// The level-by-level builder (kdtree_build.h; seed 004 section 11.2, over all three axes): every
// node of a level is processed together over flat arrays, each step an element-wise loop
// (parallelFor: a kernel), a scan or a segmented reduction (flat_primitives.h: one CUB call
// each), so the same steps run on the GPU. Per level:
//   nodes:     box, triangle count, segments of the triangle list and of each axis's events;
//   triangles: `slot` -> triangle id and owner node (a triangle in two nodes has two slots);
//   events:    per axis, node by node, each node's in kdEventLess order; an event names its slot.
// Steps: (1) scan event counts per axis, evaluate every event (evaluateEvent) and reduce per node
// to the best split (betterSplit); (2) the leaf rule (shouldSplit), ranks of split nodes; (3) the
// split axis's events flag their slots' sides (eventSides: each flag has one writer);
// (4) leaves' triangles out, sorted; nodes out; (5) scans of the flags place every slot and
// event in its child's segment, order kept, so the children's lists stay sorted.
#include <algorithm>
#include <array>
#include <numeric>

#include "gvdp/base/error.h"
#include "gvdp/mesh/flat_primitives.h"
#include "gvdp/mesh/kdtree_build.h"

namespace gvdp::detail {
namespace {

struct Level {
  std::vector<Box3f> box;
  std::vector<uint32_t> triBegin;                // nodes + 1
  std::array<std::vector<uint32_t>, 3> evBegin;  // nodes + 1 per axis
  std::vector<uint32_t> tri, triOwner;           // per slot
  std::array<std::vector<KdEvent>, 3> ev;        // triangleAndType: slot << 2 | type
  std::array<std::vector<uint32_t>, 3> evOwner;  // per event

  int64_t nodes() const { return static_cast<int64_t>(box.size()); }
};

KdEvent withSlot(KdEvent e, uint32_t slot) {
  return {e.pos, slot << 2 | eventType(e)};
}

Level rootLevel(const std::vector<Box3f>& boxes, Box3f bounds) {
  Level l;
  auto n = static_cast<int64_t>(boxes.size());
  l.box = {bounds};
  l.triBegin = {0, static_cast<uint32_t>(n)};
  l.tri.resize(boxes.size());
  std::iota(l.tri.begin(), l.tri.end(), 0u);
  l.triOwner.assign(boxes.size(), 0);
  // Events in triangle order (a scan of 1 or 2 per triangle), then sorted: the three axes at once.
  parallelFor(
      3,
      [&](int64_t a) {
        int axis = static_cast<int>(a);
        std::vector<KdEvent>& ev = l.ev[axis];
        ev = kdRootEvents(boxes, axis);
        l.evBegin[axis] = {0, static_cast<uint32_t>(ev.size())};
        l.evOwner[axis].assign(ev.size(), 0);
      },
      1);
  return l;
}

}  // namespace

KdTree buildKdTreeParallel(const Mesh& mesh) {
  std::vector<Box3f> boxes = kdTriangleBoxes(mesh);
  KdTree tree;
  tree.bounds = kdRootBox(boxes);
  Level l = rootLevel(boxes, tree.bounds);
  tree.nodes.resize(1);
  uint32_t nodeBase = 0;
  for (int depth = 0; l.nodes() > 0; ++depth) {
    const int64_t m = l.nodes();
    auto triCount = [&](int64_t j) { return l.triBegin[j + 1] - l.triBegin[j]; };

    // (1) the best split of every node over its three axes
    std::vector<KdSplit> best(static_cast<size_t>(m), noSplit());
    for (int axis = 0; axis < 3; ++axis) {
      const std::vector<KdEvent>& ev = l.ev[axis];
      std::vector<KdEventCounts> before;
      exclusiveScan<KdEventCounts>(
          static_cast<int64_t>(ev.size()), [&](int64_t i) { return countsOf(ev[i]); }, before);
      std::vector<KdSplit> axisBest;
      segmentedReduce<KdSplit>(
          l.evBegin[axis], m, noSplit(),
          [&](int64_t i) {
            uint32_t j = l.evOwner[axis][i], b = l.evBegin[axis][j];
            return evaluateEvent(ev.data(), static_cast<uint32_t>(i), b, l.evBegin[axis][j + 1],
                                 before[i] - before[b], triCount(j), l.box[j], axis);
          },
          betterSplit, axisBest);
      parallelFor(m, [&](int64_t j) {
        if (betterSplit(axisBest[j], best[j])) best[j] = axisBest[j];
      });
    }

    // (2) which nodes split, and their ranks among the level's split nodes and leaves
    std::vector<uint8_t> split(static_cast<size_t>(m));
    parallelFor(m,
                [&](int64_t j) { split[j] = shouldSplit(l.box[j], triCount(j), depth, best[j]); });
    std::vector<uint32_t> rank, leafOffset;
    exclusiveScan<uint32_t>(
        m, [&](int64_t j) { return uint32_t{split[j]}; }, rank);
    exclusiveScan<uint32_t>(
        m, [&](int64_t j) { return split[j] ? 0u : triCount(j); }, leafOffset);
    const int64_t splits = rank[m];

    // (3) the sides of every slot of a split node, from the events of its split axis
    const auto slots = static_cast<int64_t>(l.tri.size());
    std::vector<uint8_t> left(static_cast<size_t>(slots), 0), right(static_cast<size_t>(slots), 0);
    for (int axis = 0; axis < 3; ++axis)
      parallelFor(static_cast<int64_t>(l.ev[axis].size()), [&](int64_t i) {
        uint32_t j = l.evOwner[axis][i];
        if (!split[j] || best[j].axis != axis) return;
        KdEvent e = l.ev[axis][i];
        uint32_t sides = eventSides(e, best[j].pos), slot = eventTriangle(e);
        uint32_t type = eventType(e);
        if (type != KD_EVENT_END) left[slot] = (sides & KD_LEFT) != 0;      // START or PLANAR
        if (type != KD_EVENT_START) right[slot] = (sides & KD_RIGHT) != 0;  // END or PLANAR
      });

    // (4) the level's nodes and leaves out; children are the next level's nodes 2 rank, +1
    const uint32_t nextBase = nodeBase + static_cast<uint32_t>(m);
    const auto leafBase = static_cast<uint32_t>(tree.leafTriangles.size());
    GVDP_CHECK(nextBase + 2 * splits <= KD_MAX_INDEX && leafBase + leafOffset[m] <= KD_MAX_INDEX,
               "kd-tree past 2^30 nodes or leaf references");
    tree.nodes.resize(nextBase + 2 * static_cast<size_t>(splits));
    tree.leafTriangles.resize(leafBase + static_cast<size_t>(leafOffset[m]));
    parallelFor(
        m,
        [&](int64_t j) {
          if (split[j]) {
            tree.nodes[nodeBase + j] =
                kdInterior(best[j].axis, best[j].pos, nextBase + 2 * rank[j]);
            return;
          }
          uint32_t first = leafBase + leafOffset[j];
          auto out = tree.leafTriangles.begin() + first;
          std::copy(l.tri.begin() + l.triBegin[j], l.tri.begin() + l.triBegin[j + 1], out);
          std::sort(out, out + triCount(j));  // the GPU: a segmented sort
          tree.nodes[nodeBase + j] = kdLeaf(first, triCount(j));
        },
        16);
    if (splits == 0) break;

    // (5) the next level: slots, then events, each placed by scans of its side flags
    Level next;
    next.box.resize(2 * static_cast<size_t>(splits));
    parallelFor(m, [&](int64_t j) {
      if (!split[j]) return;
      next.box[2 * rank[j]] = leftBox(l.box[j], best[j].axis, best[j].pos);
      next.box[2 * rank[j] + 1] = rightBox(l.box[j], best[j].axis, best[j].pos);
    });
    auto goes = [&](const std::vector<uint8_t>& side, uint32_t slot) {
      return uint32_t{split[l.triOwner[slot]] && side[slot]};
    };
    std::vector<uint32_t> scanL, scanR;
    exclusiveScan<uint32_t>(
        slots, [&](int64_t i) { return goes(left, static_cast<uint32_t>(i)); }, scanL);
    exclusiveScan<uint32_t>(
        slots, [&](int64_t i) { return goes(right, static_cast<uint32_t>(i)); }, scanR);
    // the children's triangle counts in child order, scanned to their segments
    std::vector<uint32_t> childTris(2 * static_cast<size_t>(splits));
    parallelFor(m, [&](int64_t j) {
      if (!split[j]) return;
      uint32_t b = l.triBegin[j], e = l.triBegin[j + 1];
      childTris[2 * rank[j]] = scanL[e] - scanL[b];
      childTris[2 * rank[j] + 1] = scanR[e] - scanR[b];
    });
    exclusiveScan<uint32_t>(
        2 * splits, [&](int64_t c) { return childTris[c]; }, next.triBegin);
    std::vector<uint32_t> slotL(static_cast<size_t>(slots)), slotR(static_cast<size_t>(slots));
    next.tri.resize(next.triBegin[2 * splits]);
    next.triOwner.resize(next.tri.size());
    parallelFor(slots, [&](int64_t i) {
      uint32_t j = l.triOwner[i];
      if (!split[j]) return;
      uint32_t b = l.triBegin[j], c = 2 * rank[j];
      if (left[i]) {
        uint32_t dst = next.triBegin[c] + scanL[i] - scanL[b];
        next.tri[dst] = l.tri[i];
        next.triOwner[dst] = c;
        slotL[i] = dst;
      }
      if (right[i]) {
        uint32_t dst = next.triBegin[c + 1] + scanR[i] - scanR[b];
        next.tri[dst] = l.tri[i];
        next.triOwner[dst] = c + 1;
        slotR[i] = dst;
      }
    });
    for (int axis = 0; axis < 3; ++axis) {
      const std::vector<KdEvent>& ev = l.ev[axis];
      const std::vector<uint32_t>& owner = l.evOwner[axis];
      const std::vector<uint32_t>& begin = l.evBegin[axis];
      auto n = static_cast<int64_t>(ev.size());
      std::vector<uint32_t> evL, evR, childEvents(2 * static_cast<size_t>(splits));
      exclusiveScan<uint32_t>(
          n, [&](int64_t i) { return goes(left, eventTriangle(ev[i])); }, evL);
      exclusiveScan<uint32_t>(
          n, [&](int64_t i) { return goes(right, eventTriangle(ev[i])); }, evR);
      parallelFor(m, [&](int64_t j) {
        if (!split[j]) return;
        childEvents[2 * rank[j]] = evL[begin[j + 1]] - evL[begin[j]];
        childEvents[2 * rank[j] + 1] = evR[begin[j + 1]] - evR[begin[j]];
      });
      exclusiveScan<uint32_t>(
          2 * splits, [&](int64_t c) { return childEvents[c]; }, next.evBegin[axis]);
      next.ev[axis].resize(next.evBegin[axis][2 * splits]);
      next.evOwner[axis].resize(next.ev[axis].size());
      parallelFor(n, [&](int64_t i) {
        uint32_t j = owner[i];
        if (!split[j]) return;
        uint32_t slot = eventTriangle(ev[i]), c = 2 * rank[j];
        if (left[slot]) {
          uint32_t dst = next.evBegin[axis][c] + evL[i] - evL[begin[j]];
          next.ev[axis][dst] = withSlot(ev[i], slotL[slot]);
          next.evOwner[axis][dst] = c;
        }
        if (right[slot]) {
          uint32_t dst = next.evBegin[axis][c + 1] + evR[i] - evR[begin[j]];
          next.ev[axis][dst] = withSlot(ev[i], slotR[slot]);
          next.evOwner[axis][dst] = c + 1;
        }
      });
    }
    l = std::move(next);
    nodeBase = nextBase;
  }
  return tree;
}

}  // namespace gvdp::detail
