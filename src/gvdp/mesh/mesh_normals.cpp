#include "gvdp/mesh/mesh_normals.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "gvdp/base/parallel.h"

namespace gvdp::detail {
namespace {

Vec3f unitOrZero(Vec3f v) {
  float l = length(v);
  return l > 0.0f ? v / l : Vec3f{0.0f, 0.0f, 0.0f};
}

// The angle at corner a between a->b and a->c (0 for a degenerate corner).
float cornerAngle(Vec3f a, Vec3f b, Vec3f c) {
  Vec3f u = unitOrZero(b - a), v = unitOrZero(c - a);
  return std::atan2(length(cross(u, v)), dot(u, v));
}

}  // namespace

MeshNormals meshNormals(const Mesh& mesh) {
  size_t triangles = mesh.triangleCount();
  std::vector<Vec3f> face(triangles);
  parallelFor(static_cast<int64_t>(triangles), [&](int64_t t) {
    face[t] = unitOrZero(
        cross(mesh.corner(t, 1) - mesh.corner(t, 0), mesh.corner(t, 2) - mesh.corner(t, 0)));
  });

  MeshNormals n;
  n.vertex.assign(mesh.vertices.size(), Vec3f{0.0f, 0.0f, 0.0f});
  for (size_t t = 0; t < triangles; ++t)
    for (int k = 0; k < 3; ++k) {
      float angle =
          cornerAngle(mesh.corner(t, k), mesh.corner(t, (k + 1) % 3), mesh.corner(t, (k + 2) % 3));
      Vec3f& v = n.vertex[mesh.indices[3 * t + k]];
      v = v + face[t] * angle;
    }
  for (Vec3f& v : n.vertex) v = unitOrZero(v);

  // Edges sorted by their vertex pair: the triangles sharing an edge are adjacent in the order.
  struct HalfEdge {
    uint32_t lo, hi, slot;  // slot: 3 * triangle + k
  };
  std::vector<HalfEdge> half(3 * triangles);
  for (size_t t = 0; t < triangles; ++t)
    for (int k = 0; k < 3; ++k) {
      uint32_t a = mesh.indices[3 * t + k], b = mesh.indices[3 * t + (k + 1) % 3];
      half[3 * t + k] = {std::min(a, b), std::max(a, b), static_cast<uint32_t>(3 * t + k)};
    }
  std::sort(half.begin(), half.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.slot < y.slot;
  });
  n.edge.assign(3 * triangles, Vec3f{0.0f, 0.0f, 0.0f});
  for (size_t i = 0; i < half.size();) {
    size_t j = i;
    Vec3f sum{0.0f, 0.0f, 0.0f};
    for (; j < half.size() && half[j].lo == half[i].lo && half[j].hi == half[i].hi; ++j)
      sum = sum + face[half[j].slot / 3];
    for (size_t k = i; k < j; ++k) n.edge[half[k].slot] = unitOrZero(sum);
    i = j;
  }
  return n;
}

}  // namespace gvdp::detail
