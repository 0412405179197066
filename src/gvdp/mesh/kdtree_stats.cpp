// kdTreeStats and sameTree (kdtree_stats.h): walks from the root with an explicit stack.
#include "gvdp/mesh/kdtree_stats.h"

#include <algorithm>
#include <vector>

namespace gvdp::detail {
namespace {

double areaOf(Box3f b) {
  double dx = double(b.hi.x) - b.lo.x, dy = double(b.hi.y) - b.lo.y, dz = double(b.hi.z) - b.lo.z;
  return dx * dy + dy * dz + dz * dx;
}

}  // namespace

KdTreeStats kdTreeStats(const KdTree& tree) {
  KdTreeStats s;
  if (tree.nodes.empty()) return s;
  double rootArea = areaOf(tree.bounds);
  struct Item {
    uint32_t node;
    Box3f box;
    int depth;
  };
  std::vector<Item> stack{{0, tree.bounds, 0}};
  while (!stack.empty()) {
    Item it = stack.back();
    stack.pop_back();
    KdNode n = tree.nodes[it.node];
    ++s.nodes;
    s.maxDepth = std::max(s.maxDepth, it.depth);
    double share = rootArea > 0.0 ? areaOf(it.box) / rootArea : 1.0;
    if (isLeaf(n)) {
      ++s.leaves;
      s.emptyLeaves += leafCount(n) == 0;
      s.leafReferences += leafCount(n);
      s.sahCost += KD_COST_INTERSECTION * leafCount(n) * share;
      continue;
    }
    s.sahCost += KD_COST_TRAVERSAL * share;
    int axis = splitAxis(n);
    float p = splitPosition(n);
    stack.push_back({rightChild(n), rightBox(it.box, axis, p), it.depth + 1});
    stack.push_back({leftChild(n), leftBox(it.box, axis, p), it.depth + 1});
  }
  s.meanLeafTriangles = s.leaves ? double(s.leafReferences) / double(s.leaves) : 0.0;
  return s;
}

bool sameTree(const KdTree& a, const KdTree& b, std::string* why) {
  auto differ = [&](const std::string& path, const std::string& what) {
    if (why) *why = "at " + (path.empty() ? std::string("the root") : path) + ": " + what;
    return false;
  };
  auto boxBits = [](Box3f x) {
    return std::vector<uint32_t>{floatBits(x.lo.x), floatBits(x.lo.y), floatBits(x.lo.z),
                                 floatBits(x.hi.x), floatBits(x.hi.y), floatBits(x.hi.z)};
  };
  if (boxBits(a.bounds) != boxBits(b.bounds)) return differ("", "root boxes differ");
  if (a.nodes.empty() || b.nodes.empty())
    return a.nodes.empty() == b.nodes.empty() ? true : differ("", "one tree is empty");
  struct Item {
    uint32_t na, nb;
    std::string path;
  };
  std::vector<Item> stack{{0, 0, ""}};
  while (!stack.empty()) {
    Item it = stack.back();
    stack.pop_back();
    KdNode x = a.nodes[it.na], y = b.nodes[it.nb];
    if (isLeaf(x) != isLeaf(y)) return differ(it.path, "a leaf against an interior node");
    if (isLeaf(x)) {
      auto fx = a.leafTriangles.begin() + leafFirst(x), fy = b.leafTriangles.begin() + leafFirst(y);
      if (leafCount(x) != leafCount(y) || !std::equal(fx, fx + leafCount(x), fy))
        return differ(it.path, "leaves of " + std::to_string(leafCount(x)) + " and " +
                                   std::to_string(leafCount(y)) + " triangles differ");
      continue;
    }
    if (splitAxis(x) != splitAxis(y) || x.payload != y.payload)
      return differ(it.path, "split " + std::to_string(splitAxis(x)) + "@" +
                                 std::to_string(splitPosition(x)) + " against " +
                                 std::to_string(splitAxis(y)) + "@" +
                                 std::to_string(splitPosition(y)));
    stack.push_back({rightChild(x), rightChild(y), it.path + "R"});
    stack.push_back({leftChild(x), leftChild(y), it.path + "L"});
  }
  return true;
}

}  // namespace gvdp::detail
