// 1-to-4 midpoint subdivision: every triangle (a, b, c) becomes (a, ab, ca), (ab, b, bc),
// (ca, bc, c), (ab, bc, ca), with one new vertex per edge shared by the triangles around it, so a
// closed (watertight) mesh stays closed and keeps its orientation. N times multiplies the
// triangles by 4^N (the bunny's 69 451 twice: 1.1 M), a way to make large meshes from small.
#pragma once

#include "gvdp/mesh/mesh.h"

namespace gvdp::detail {

Mesh subdivide(const Mesh& mesh, int times = 1);

// An icosahedron subdivided `times` times, its vertices pushed to the unit sphere: 20 * 4^times
// triangles (times 8: 1,310,720), a closed mesh of any size made anywhere.
Mesh icosphere(int times);

}  // namespace gvdp::detail
