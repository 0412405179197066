// Building the kd-tree of kdtree.h over a mesh: the tree as host vectors, and its builders.
// Every builder applies kdtree.h's rules, so their trees are sameTree (kdtree_stats.h).
#pragma once

#include <vector>

#include "gvdp/mesh/kdtree.h"
#include "gvdp/mesh/mesh.h"

namespace gvdp::detail {

struct KdTree {
  std::vector<KdNode> nodes;            // node 0 is the root
  std::vector<uint32_t> leafTriangles;  // each leaf's triangles, ascending ids
  Box3f bounds = emptyBox();            // the root's box

  KdTreeView view() const { return {nodes.data(), leafTriangles.data(), bounds}; }
};

// Every triangle's kdTriangleBox, and the union of them (the root's box).
std::vector<Box3f> kdTriangleBoxes(const Mesh& mesh);
Box3f kdRootBox(const std::vector<Box3f>& boxes);
// The root's events along `axis` (a planar event for a flat extent, else a start and an end per
// triangle), sorted by kdEventLess: both builders start from them.
std::vector<KdEvent> kdRootEvents(const std::vector<Box3f>& boxes, int axis);

// Wald and Havran's O(N log N) builder, one thread: events sorted once per axis; each node
// sweeps its three sorted lists for the best plane, then splits them into its children's lists
// in order (no clipping, so no re-sorting). Nodes are stored depth first.
KdTree buildKdTreeSequential(const Mesh& mesh);

// Seed 004's level-by-level builder on the thread pool: all nodes of a level together, in sorts,
// scans and segmented reductions over flat arrays (kdtree_parallel.cpp), the steps a GPU builder
// makes with CUB. Nodes are stored level by level; the tree is sameTree as the sequential one.
KdTree buildKdTreeParallel(const Mesh& mesh);

// Where a GPU build's wall time went, read at its synchronisation points: the upload and the root
// level, the levels, the download of the tree.
struct KdBuildPhases {
  double rootMs = 0.0, levelsMs = 0.0, downloadMs = 0.0;
  int levels = 0;
};

// The same level-by-level builder on the GPU (kdtree_cuda.cu): each step one CUB call or one
// element-wise kernel over device arrays, the rules the same GVDP_HD functions, nodes and leaf
// triangles stored as buildKdTreeParallel stores them. Uploads the mesh, downloads the tree; on
// its own stream, finished on return. Throws InputError in builds without CUDA.
KdTree buildKdTreeCuda(const Mesh& mesh, KdBuildPhases* phases = nullptr);

}  // namespace gvdp::detail
