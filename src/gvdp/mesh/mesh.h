// A triangle mesh: float vertices and three uint32 vertex indices per triangle (mesh_io.h reads
// and writes them, mesh_subdivide.h refines them). Invariant after validateMesh: every
// coordinate is finite, every index names a vertex, there is at least one triangle.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gvdp/base/vecmath.h"
#include "gvdp/mesh/box.h"

namespace gvdp::detail {

struct Mesh {
  std::vector<Vec3f> vertices;
  std::vector<uint32_t> indices;  // 3 per triangle

  size_t triangleCount() const { return indices.size() / 3; }
  Vec3f corner(size_t triangle, int k) const { return vertices[indices[3 * triangle + k]]; }
};

// The box of every vertex a triangle uses.
Box3f meshBounds(const Mesh& mesh);
Box3f triangleBounds(const Mesh& mesh, size_t triangle);

// The checks every reader ends with; `name` (the file) starts the one-line InputError.
void validateMesh(const Mesh& mesh, const std::string& name);

// The documented placement of a mesh in a world: its bounding box centred on `centre`, its longest
// side scaled to `size` (uniformly, so shapes keep their proportions).
constexpr float MESH_PLACED_SIZE = 1.0f;
void placeMesh(Mesh& mesh, Vec3f centre = {0.0f, 0.0f, 0.0f}, float size = MESH_PLACED_SIZE);

}  // namespace gvdp::detail
