// What a kd-tree is, independent of how a builder stored it: its figures (node and leaf counts,
// depth, the SAH cost of the whole tree) and the canonical comparison of two trees.
#pragma once

#include <cstddef>
#include <string>

#include "gvdp/mesh/kdtree_build.h"

namespace gvdp::detail {

struct KdTreeStats {
  size_t nodes = 0, leaves = 0, emptyLeaves = 0, leafReferences = 0;
  int maxDepth = 0;
  double meanLeafTriangles = 0.0;  // over all leaves, empty ones included
  // The tree's SAH cost: sum over interior nodes of TRAVERSAL * A(node) / A(root), over leaves
  // of INTERSECTION * triangles * A(leaf) / A(root) (in double).
  double sahCost = 0.0;
};
KdTreeStats kdTreeStats(const KdTree& tree);

// The same tree: equal root boxes, and a walk from both roots meets, node for node, the same
// split axis and position (bits) or leaves of the same triangle sets. Storage order is free.
// On a difference, `why` (when given) says where: the path from the root (L/R) and what differs.
bool sameTree(const KdTree& a, const KdTree& b, std::string* why = nullptr);

}  // namespace gvdp::detail
