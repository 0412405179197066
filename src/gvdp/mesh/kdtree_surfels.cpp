#include "gvdp/mesh/kdtree_surfels.h"

#include <cstdint>

namespace gvdp::detail {
namespace {

struct Sums {
  Vec3f weightedCentre{0.0f, 0.0f, 0.0f};  // sum of area * centroid
  Vec3f weightedNormal{0.0f, 0.0f, 0.0f};  // sum of area * unit normal (half the cross product)
  float area = 0.0f;
  Box3f box = emptyBox();
};

Sums combine(const Sums& a, const Sums& b) {
  return {a.weightedCentre + b.weightedCentre, a.weightedNormal + b.weightedNormal, a.area + b.area,
          merge(a.box, b.box)};
}

KdSurfel surfelOf(const Sums& s) {
  KdSurfel k;
  k.box = s.box;
  k.centre = s.area > 0.0f ? s.weightedCentre / s.area : (s.box.lo + s.box.hi) * 0.5f;
  float n = length(s.weightedNormal);
  // Normals that mostly cancel (both sides of a thin part) give no direction.
  k.normal = n > 0.05f * s.area && n > 0.0f ? s.weightedNormal / n : Vec3f{0.0f, 0.0f, 0.0f};
  return k;
}

}  // namespace

std::vector<KdSurfel> kdSurfels(const Mesh& mesh, const KdTree& tree) {
  std::vector<Sums> sums(tree.nodes.size());
  std::vector<KdSurfel> surfels(tree.nodes.size());
  // Post-order without recursion: a node is finished once both its children are.
  struct Visit {
    uint32_t node;
    bool childrenDone;
  };
  std::vector<Visit> stack{{0, false}};
  while (!stack.empty()) {
    Visit v = stack.back();
    stack.pop_back();
    KdNode n = tree.nodes[v.node];
    Sums s;
    if (isLeaf(n)) {
      for (uint32_t k = 0; k < leafCount(n); ++k) {
        uint32_t t = tree.leafTriangles[leafFirst(n) + k];
        Vec3f a = mesh.corner(t, 0), b = mesh.corner(t, 1), c = mesh.corner(t, 2);
        Vec3f half = cross(b - a, c - a) * 0.5f;
        float area = length(half);
        s.weightedCentre = s.weightedCentre + (a + b + c) * (area / 3.0f);
        s.weightedNormal = s.weightedNormal + half;
        s.area += area;
        s.box = merge(merge(merge(s.box, a), b), c);
      }
    } else if (!v.childrenDone) {
      stack.push_back({v.node, true});
      stack.push_back({leftChild(n), false});
      stack.push_back({rightChild(n), false});
      continue;
    } else {
      s = combine(sums[leftChild(n)], sums[rightChild(n)]);
    }
    sums[v.node] = s;
    surfels[v.node] = surfelOf(s);
  }
  return surfels;
}

}  // namespace gvdp::detail
