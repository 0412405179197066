// Midpoint subdivision (mesh_subdivide.h). Edges are found by sorting (smaller, larger) vertex
// pairs: one new vertex per distinct edge, numbered in the sorted order, so the result does not
// depend on a hash table's iteration order.
#include "gvdp/mesh/mesh_subdivide.h"

#include <algorithm>

#include "gvdp/base/error.h"

namespace gvdp::detail {
namespace {

uint64_t edgeKey(uint32_t a, uint32_t b) {
  return a < b ? (uint64_t{a} << 32 | b) : (uint64_t{b} << 32 | a);
}

Mesh subdivideOnce(const Mesh& mesh) {
  size_t n = mesh.triangleCount();
  GVDP_INPUT_CHECK(4 * n < (size_t{1} << 30), "subdivision to ", 4 * n,
                   " triangles (at most 2^30)");
  std::vector<uint64_t> edges(3 * n);
  for (size_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k)
      edges[3 * t + k] = edgeKey(mesh.indices[3 * t + k], mesh.indices[3 * t + (k + 1) % 3]);
  std::vector<uint64_t> unique = edges;
  std::sort(unique.begin(), unique.end());
  unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
  Mesh out;
  out.vertices = mesh.vertices;
  out.vertices.reserve(mesh.vertices.size() + unique.size());
  for (uint64_t e : unique) {
    Vec3f a = mesh.vertices[e >> 32], b = mesh.vertices[e & 0xffffffffu];
    out.vertices.push_back((a + b) * 0.5f);
  }
  auto midpoint = [&](size_t corner) {
    size_t i = static_cast<size_t>(std::lower_bound(unique.begin(), unique.end(), edges[corner]) -
                                   unique.begin());
    return static_cast<uint32_t>(mesh.vertices.size() + i);
  };
  out.indices.reserve(12 * n);
  for (size_t t = 0; t < n; ++t) {
    uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1], c = mesh.indices[3 * t + 2];
    uint32_t ab = midpoint(3 * t), bc = midpoint(3 * t + 1), ca = midpoint(3 * t + 2);
    out.indices.insert(out.indices.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
  }
  return out;
}

}  // namespace

Mesh subdivide(const Mesh& mesh, int times) {
  GVDP_INPUT_CHECK(times >= 0 && times <= 12, "subdivision times ", times, " (expected 0..12)");
  Mesh out = mesh;
  for (int i = 0; i < times; ++i) out = subdivideOnce(out);
  return out;
}

Mesh icosphere(int times) {
  const float t = 1.6180339887f;
  Mesh m;
  m.vertices = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  m.indices = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
               4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
               6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  if (times > 0) m = subdivide(m, times);
  for (Vec3f& v : m.vertices) v = normalize(v);
  return m;
}

}  // namespace gvdp::detail
