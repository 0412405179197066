// Angle-weighted pseudonormals (Baerentzen and Aanaes 2005, "Signed distance computation using the
// angle weighted pseudonormal"): per vertex the sum of its triangles' unit normals weighted by
// the triangle's angle at the vertex, per edge the sum of the unit normals of the triangles that
// share it. For a closed, consistently oriented mesh the pseudonormal of the feature (face, edge
// or vertex) nearest to a point q says on which side q lies: dot(q - nearest, n) > 0 outside.
// The vertex normals, interpolated, also shade the surface.
#pragma once

#include <vector>

#include "gvdp/mesh/mesh.h"

namespace gvdp::detail {

struct MeshNormals {
  std::vector<Vec3f> vertex;  // unit, angle-weighted; one per vertex
  std::vector<Vec3f> edge;    // unit; three per triangle: edge k runs from corner k to k + 1
};

// Degenerate (zero-area) triangles add nothing; a vertex or edge with no other triangle keeps the
// normal of the one it has (open meshes: the sign is then right near the surface only).
MeshNormals meshNormals(const Mesh& mesh);

}  // namespace gvdp::detail
