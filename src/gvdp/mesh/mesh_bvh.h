// The mesh's level of detail for distance queries (surface_queries.h): a bounding volume
// hierarchy over the triangles in Morton order of their centroids (a binary radix tree: each
// interior node halves its cell of the mesh's bounding cube along the next bit of x, y, z), each
// node with the tight box of its triangles and a surfel standing for them, a disc at their
// area-weighted centroid across their area-weighted normal. A query for voxels of size v takes a
// node at most MESH_SURFEL_VOXELS v wide as its surfel instead of visiting its triangles.
// Why not the kd-tree: its SAH nodes are slabs, wide in two directions and thin in the third, so
// no node of a coarse voxel's reach is narrow enough to stand in for its triangles until deep
// down: 1047 node visits for a voxel of 1/8 (573 of them interior), 389 at 1/16 (measured on
// the bunny). The cells here are near-cubes: the nodes a reach meets are about its area in cells.
#pragma once

#include <cstdint>
#include <vector>

#include "gvdp/mesh/mesh.h"

namespace gvdp::detail {

constexpr uint32_t MESH_BVH_LEAF = 4;     // a node of at most this many triangles is a leaf
constexpr int MESH_BVH_MORTON_BITS = 10;  // per axis: 30-bit codes, a depth of at most 31
constexpr int MESH_BVH_STACK = 3 * MESH_BVH_MORTON_BITS + 2;

struct MeshBvhNode {
  Box3f box;       // of its triangles
  Vec3f centre;    // the surfel's
  Vec3f normal;    // unit, or zero where the normals cancel (a thin part folded inside the node)
  uint32_t first;  // interior: its left child (the right one follows); leaf: its first triangle
  uint32_t count;  // 0: interior; else the leaf's triangles, triangles[first, first + count)
};

// The longest side of a node's box.
GVDP_HD GVDP_INLINE float surfelWidth(const MeshBvhNode& n) {
  return maxComponent(n.box.hi - n.box.lo);
}

// A hierarchy in memory it does not own (host or device).
struct MeshBvhView {
  const MeshBvhNode* nodes;   // node 0 is the root
  const uint32_t* triangles;  // the leaves' triangle ids
};

struct MeshBvh {
  std::vector<MeshBvhNode> nodes;
  std::vector<uint32_t> triangles;

  MeshBvhView view() const { return {nodes.data(), triangles.data()}; }
};

// Built on the host in O(N log N) (the sort); a mesh of at least one triangle.
MeshBvh buildMeshBvh(const Mesh& mesh);

}  // namespace gvdp::detail
