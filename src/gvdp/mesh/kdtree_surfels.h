// A level of detail for distance queries (kdtree_nearest.h): per kd-tree node a surfel standing
// for the triangles under it, a disc at their area-weighted centroid, across their area-weighted
// normal, as wide as their box, and the box itself (a tighter bound than the split planes). A query
// for voxels of size v takes a node whose triangles' box is at most MESH_SURFEL_VOXELS v wide as
// its surfel, instead of visiting its triangles: coarse voxels then cost tens of nodes, where exact
// distances over the small triangles of a fine mesh cost thousands (lattice frames 10x slower),
// with an error below the node's width. Fine voxels never use them (a node is at least a triangle
// wide), so fine levels stay exact.
#pragma once

#include <vector>

#include "gvdp/mesh/kdtree_build.h"

namespace gvdp::detail {

struct KdSurfel {
  Box3f box;  // of the node's triangles (empty: none); also bounds distances to them
  Vec3f centre;
  Vec3f normal;  // unit, or zero where the normals cancel (a thin part folded inside the node)
};

// The longest side of a surfel's box (negative for a node without triangles).
GVDP_HD GVDP_INLINE float surfelWidth(const KdSurfel& s) {
  return maxComponent(s.box.hi - s.box.lo);
}

// One per node of `tree`, in its node order.
std::vector<KdSurfel> kdSurfels(const Mesh& mesh, const KdTree& tree);

}  // namespace gvdp::detail
