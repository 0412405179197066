#include "gvdp/mesh/mesh_bvh.h"

#include <algorithm>
#include <numeric>

#include "gvdp/base/error.h"

namespace gvdp::detail {
namespace {

// The 10 bits of x spread to every third bit.
uint32_t spreadBits(uint32_t x) {
  x &= 0x3ffu;
  x = (x | x << 16) & 0x030000ffu;
  x = (x | x << 8) & 0x0300f00fu;
  x = (x | x << 4) & 0x030c30c3u;
  x = (x | x << 2) & 0x09249249u;
  return x;
}

struct Sums {
  Vec3f weightedCentre{0.0f, 0.0f, 0.0f};  // sum of area * centroid
  Vec3f weightedNormal{0.0f, 0.0f, 0.0f};  // sum of area * unit normal (half the cross product)
  float area = 0.0f;
  Box3f box = emptyBox();
};

Sums combine(const Sums& a, const Sums& b) {
  return {a.weightedCentre + b.weightedCentre, a.weightedNormal + b.weightedNormal, a.area + b.area,
          merge(a.box, b.box)};
}

void setSurfel(MeshBvhNode& node, const Sums& s) {
  node.box = s.box;
  node.centre = s.area > 0.0f ? s.weightedCentre / s.area : (s.box.lo + s.box.hi) * 0.5f;
  float n = length(s.weightedNormal);
  // Normals that mostly cancel (both sides of a thin part) give no direction.
  node.normal = n > 0.05f * s.area && n > 0.0f ? s.weightedNormal / n : Vec3f{0.0f, 0.0f, 0.0f};
}

struct Builder {
  const Mesh& mesh;
  std::vector<uint32_t> codes;  // per triangle
  MeshBvh& bvh;

  // The node `at` over triangles [b, e) of bvh.triangles, whose codes agree above `bit`.
  Sums build(uint32_t at, uint32_t b, uint32_t e, int bit) {
    uint32_t split = e;
    while (e - b > MESH_BVH_LEAF && bit >= 0) {  // the first triangle with the bit set
      uint32_t mask = 1u << bit;
      split = static_cast<uint32_t>(
          std::partition_point(bvh.triangles.begin() + b, bvh.triangles.begin() + e,
                               [&](uint32_t t) { return (codes[t] & mask) == 0; }) -
          bvh.triangles.begin());
      if (split != b && split != e) break;
      --bit;  // all on one side: the next bit, no node
      split = e;
    }
    if (split == e || split == b) {
      Sums s;
      for (uint32_t i = b; i < e; ++i) {
        uint32_t t = bvh.triangles[i];
        Vec3f x = mesh.corner(t, 0), y = mesh.corner(t, 1), z = mesh.corner(t, 2);
        Vec3f half = cross(y - x, z - x) * 0.5f;
        float area = length(half);
        s.weightedCentre = s.weightedCentre + (x + y + z) * (area / 3.0f);
        s.weightedNormal = s.weightedNormal + half;
        s.area += area;
        s.box = merge(merge(merge(s.box, x), y), z);
      }
      bvh.nodes[at].first = b;
      bvh.nodes[at].count = e - b;
      setSurfel(bvh.nodes[at], s);
      return s;
    }
    auto left = static_cast<uint32_t>(bvh.nodes.size());
    GVDP_CHECK(left + 2 <= UINT32_MAX - 1, "mesh hierarchy past 2^32 nodes");
    bvh.nodes.resize(bvh.nodes.size() + 2);
    bvh.nodes[at].first = left;
    bvh.nodes[at].count = 0;
    Sums s = combine(build(left, b, split, bit - 1), build(left + 1, split, e, bit - 1));
    setSurfel(bvh.nodes[at], s);
    return s;
  }
};

}  // namespace

MeshBvh buildMeshBvh(const Mesh& mesh) {
  const auto n = static_cast<uint32_t>(mesh.triangleCount());
  GVDP_CHECK(n > 0, "mesh hierarchy of no triangles");
  Box3f bounds = meshBounds(mesh);
  float side = std::max(maxComponent(bounds.hi - bounds.lo), 1e-30f);
  const float cells = static_cast<float>(1 << MESH_BVH_MORTON_BITS);
  std::vector<uint32_t> codes(n);
  for (uint32_t t = 0; t < n; ++t) {
    Vec3f c = (mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0f;
    Vec3f q = (c - bounds.lo) * (cells / side);
    auto cell = [&](float x) { return static_cast<uint32_t>(std::clamp(x, 0.0f, cells - 1.0f)); };
    codes[t] = spreadBits(cell(q.x)) << 2 | spreadBits(cell(q.y)) << 1 | spreadBits(cell(q.z));
  }
  MeshBvh bvh;
  bvh.triangles.resize(n);
  std::iota(bvh.triangles.begin(), bvh.triangles.end(), 0u);
  std::sort(bvh.triangles.begin(), bvh.triangles.end(), [&](uint32_t a, uint32_t b) {
    return codes[a] < codes[b] || (codes[a] == codes[b] && a < b);
  });
  bvh.nodes.reserve(2 * size_t{n} / MESH_BVH_LEAF + 1);
  bvh.nodes.resize(1);
  Builder{mesh, std::move(codes), bvh}.build(0, 0, n, 3 * MESH_BVH_MORTON_BITS - 1);
  return bvh;
}

}  // namespace gvdp::detail
