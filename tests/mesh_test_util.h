// Small meshes made in the tests (never downloaded data): a cube (flat, axis-aligned triangles),
// an icosphere, a random triangle soup, stacked flat squares; and the closed-mesh check.
#pragma once

#include <algorithm>
#include <map>
#include <random>
#include <utility>

#include "gvdp/mesh/mesh.h"
#include "gvdp/mesh/mesh_subdivide.h"

namespace gvdp::detail::test {

// The cube [lo, lo + size]^3: 8 vertices, 12 triangles, outward facing, closed.
inline Mesh cubeMesh(float lo = -1.0f, float size = 2.0f) {
  Mesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.push_back({lo + size * (i & 1), lo + size * ((i >> 1) & 1), lo + size * (i >> 2)});
  const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads)
    m.indices.insert(m.indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
  return m;
}

using detail::icosphere;  // mesh/mesh_subdivide.h

// `n` random triangles in [0, 1]^3 of sizes up to `size`; a few of them flat on a grid plane.
inline Mesh randomSoup(int n, float size, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Mesh m;
  for (int i = 0; i < n; ++i) {
    Vec3f c{u(rng), u(rng), u(rng)};
    for (int k = 0; k < 3; ++k) {
      Vec3f v = c + Vec3f{u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f} * size;
      if (i % 7 == 0) v.z = 0.25f * static_cast<float>(i % 4);  // flat in z at a shared plane
      m.vertices.push_back(v);
      m.indices.push_back(static_cast<uint32_t>(m.vertices.size() - 1));
    }
  }
  return m;
}

// Flat squares (grids of 4x4 quads) stacked at z = 0, 0.2, ..., 1: splits land in their planes.
inline Mesh stackedSquares() {
  Mesh m;
  for (int level = 0; level < 6; ++level) {
    auto base = static_cast<uint32_t>(m.vertices.size());
    float z = 0.2f * static_cast<float>(level), shift = 0.05f * static_cast<float>(level);
    for (int j = 0; j <= 4; ++j)
      for (int i = 0; i <= 4; ++i)
        m.vertices.push_back(
            {shift + 0.25f * static_cast<float>(i), 0.25f * static_cast<float>(j), z});
    for (uint32_t j = 0; j < 4; ++j)
      for (uint32_t i = 0; i < 4; ++i) {
        uint32_t a = base + 5 * j + i;
        m.indices.insert(m.indices.end(), {a, a + 1, a + 6, a, a + 6, a + 5});
      }
  }
  return m;
}

// Closed and consistently oriented: every directed edge appears once and its reverse once.
inline bool isClosed(const Mesh& m) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (size_t t = 0; t < m.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) ++directed[{m.indices[3 * t + k], m.indices[3 * t + (k + 1) % 3]}];
  return std::all_of(directed.begin(), directed.end(), [&](const auto& e) {
    auto back = directed.find({e.first.second, e.first.first});
    return e.second == 1 && back != directed.end() && back->second == 1;
  });
}

}  // namespace gvdp::detail::test
