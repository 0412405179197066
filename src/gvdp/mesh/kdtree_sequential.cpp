// The sequential full-SAH builder (kdtree_build.h; Wald and Havran 2006, section 4 without
// clipping; the rules are kdtree.h's). A node holds its events of the three axes, each list in
// kdEventLess order; a split classifies its triangles by the events of the split axis
// (eventSides) and filters the three lists into the children's, which stay sorted.
#include <algorithm>
#include <array>

#include "gvdp/base/error.h"
#include "gvdp/mesh/kdtree_build.h"

namespace gvdp::detail {

std::vector<Box3f> kdTriangleBoxes(const Mesh& mesh) {
  std::vector<Box3f> boxes(mesh.triangleCount());
  for (size_t t = 0; t < boxes.size(); ++t)
    boxes[t] = kdTriangleBox(mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2));
  return boxes;
}

std::vector<KdEvent> kdRootEvents(const std::vector<Box3f>& boxes, int axis) {
  std::vector<KdEvent> ev;
  ev.reserve(2 * boxes.size());
  for (size_t t = 0; t < boxes.size(); ++t) {
    float lo = component(boxes[t].lo, axis), hi = component(boxes[t].hi, axis);
    auto tri = static_cast<uint32_t>(t);
    if (lo == hi) {
      ev.push_back(kdEvent(lo, tri, KD_EVENT_PLANAR));
    } else {
      ev.push_back(kdEvent(lo, tri, KD_EVENT_START));
      ev.push_back(kdEvent(hi, tri, KD_EVENT_END));
    }
  }
  std::sort(ev.begin(), ev.end(), kdEventLess);  // the GPU: a radix sort on eventKey
  return ev;
}

Box3f kdRootBox(const std::vector<Box3f>& boxes) {
  Box3f b = emptyBox();
  for (const Box3f& t : boxes) b = merge(b, t);
  return b;
}

namespace {

using Events = std::array<std::vector<KdEvent>, 3>;

// The best candidate of one axis: the sweep of Wald and Havran over distinct positions, with
// the PLANAR events of a position counted left (kdtree.h's counts).
KdSplit bestSplitOnAxis(const std::vector<KdEvent>& ev, Box3f box, int axis, uint32_t n) {
  KdSplit best = noSplit();
  uint32_t left = 0, right = n;
  size_t i = 0;
  while (i < ev.size()) {
    float p = ev[i].pos;
    uint32_t ends = 0, planars = 0, starts = 0;
    for (; i < ev.size() && ev[i].pos == p && eventType(ev[i]) == KD_EVENT_END; ++i) ++ends;
    for (; i < ev.size() && ev[i].pos == p && eventType(ev[i]) == KD_EVENT_PLANAR; ++i) ++planars;
    for (; i < ev.size() && ev[i].pos == p && eventType(ev[i]) == KD_EVENT_START; ++i) ++starts;
    right -= ends + planars;
    left += planars;
    KdSplit s = evaluateSplit(box, axis, p, left, right);
    if (betterSplit(s, best)) best = s;
    left += starts;
  }
  return best;
}

struct Builder {
  KdTree& tree;
  std::vector<uint8_t> sides;  // per triangle, for the node being split

  void build(uint32_t node, Box3f box, Events events, int depth) {
    uint32_t n = 0;
    for (KdEvent e : events[0]) n += eventType(e) != KD_EVENT_END;
    KdSplit best = noSplit();
    for (int axis = 0; axis < 3; ++axis) {
      KdSplit s = bestSplitOnAxis(events[axis], box, axis, n);
      if (betterSplit(s, best)) best = s;
    }
    if (!shouldSplit(box, n, depth, best)) {
      size_t first = tree.leafTriangles.size();
      GVDP_CHECK(first + n <= KD_MAX_INDEX, "kd-tree leaf references past 2^30");
      for (KdEvent e : events[0])
        if (eventType(e) != KD_EVENT_END) tree.leafTriangles.push_back(eventTriangle(e));
      std::sort(tree.leafTriangles.begin() + static_cast<std::ptrdiff_t>(first),
                tree.leafTriangles.end());
      tree.nodes[node] = kdLeaf(static_cast<uint32_t>(first), n);
      return;
    }
    for (KdEvent e : events[0]) sides[eventTriangle(e)] = 0;
    for (KdEvent e : events[best.axis])
      sides[eventTriangle(e)] |= static_cast<uint8_t>(eventSides(e, best.pos));
    Events left, right;
    for (int axis = 0; axis < 3; ++axis) {
      for (KdEvent e : events[axis]) {
        uint8_t s = sides[eventTriangle(e)];
        if (s & KD_LEFT) left[axis].push_back(e);
        if (s & KD_RIGHT) right[axis].push_back(e);
      }
      events[axis] = {};  // the parent's lists are no longer needed: free them before recursing
    }
    auto child = static_cast<uint32_t>(tree.nodes.size());
    GVDP_CHECK(child + 2 <= KD_MAX_INDEX, "kd-tree nodes past 2^30");
    tree.nodes.resize(tree.nodes.size() + 2);
    tree.nodes[node] = kdInterior(best.axis, best.pos, child);
    build(child, leftBox(box, best.axis, best.pos), std::move(left), depth + 1);
    build(child + 1, rightBox(box, best.axis, best.pos), std::move(right), depth + 1);
  }
};

}  // namespace

KdTree buildKdTreeSequential(const Mesh& mesh) {
  std::vector<Box3f> boxes = kdTriangleBoxes(mesh);
  KdTree tree;
  tree.bounds = kdRootBox(boxes);
  Events events;
  for (int axis = 0; axis < 3; ++axis) events[axis] = kdRootEvents(boxes, axis);
  tree.nodes.resize(1);
  Builder builder{tree, std::vector<uint8_t>(boxes.size(), 0)};
  builder.build(0, tree.bounds, std::move(events), 0);
  return tree;
}

}  // namespace gvdp::detail
