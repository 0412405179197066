// Bounds, validation and placement of a Mesh (mesh.h).
#include "gvdp/mesh/mesh.h"

#include <cmath>

#include "gvdp/base/error.h"

namespace gvdp::detail {

Box3f triangleBounds(const Mesh& mesh, size_t triangle) {
  Box3f b = emptyBox();
  for (int k = 0; k < 3; ++k) b = merge(b, mesh.corner(triangle, k));
  return b;
}

Box3f meshBounds(const Mesh& mesh) {
  Box3f b = emptyBox();
  for (uint32_t i : mesh.indices) b = merge(b, mesh.vertices[i]);
  return b;
}

void validateMesh(const Mesh& mesh, const std::string& name) {
  GVDP_INPUT_CHECK(!mesh.indices.empty(), name, ": no faces");
  GVDP_INPUT_CHECK(mesh.indices.size() % 3 == 0, name, ": a triangle without three vertices");
  GVDP_INPUT_CHECK(mesh.triangleCount() < (size_t{1} << 30), name, ": ", mesh.triangleCount(),
                   " triangles (at most 2^30)");
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    Vec3f v = mesh.vertices[i];
    GVDP_INPUT_CHECK(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z), name,
                     ": vertex ", i, " is not finite (", v.x, " ", v.y, " ", v.z, ")");
  }
  for (size_t i = 0; i < mesh.indices.size(); ++i)
    GVDP_INPUT_CHECK(mesh.indices[i] < mesh.vertices.size(), name, ": face ", i / 3,
                     " uses vertex ", mesh.indices[i], " of ", mesh.vertices.size());
}

void placeMesh(Mesh& mesh, Vec3f centre, float size) {
  Box3f b = meshBounds(mesh);
  Vec3f mid = (b.lo + b.hi) * 0.5f;
  float longest = maxComponent(b.hi - b.lo);
  float scale = longest > 0.0f ? size / longest : 1.0f;
  for (Vec3f& v : mesh.vertices) v = centre + (v - mid) * scale;
}

}  // namespace gvdp::detail
