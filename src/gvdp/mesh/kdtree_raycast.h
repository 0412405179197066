// Closest-hit ray casts through a kd-tree (kdtree.h) and, for reference, through every triangle.
// GVDP_HD over PODs so the GPU can run the same body. The triangle test is Moller-Trumbore
// (hits with t in (tMin, best), edges inclusive); traversal is the classic front-to-back walk
// with a stack of far children (pbrt-v3 4.4.4): a leaf's triangles are all tested, and the walk
// stops once the best hit lies within the interval of the leaf just finished.
#pragma once

#include <cstdint>
#include <limits>

#include "gvdp/base/ray.h"
#include "gvdp/mesh/kdtree.h"

namespace gvdp::detail {

struct MeshView {
  const Vec3f* vertices;
  const uint32_t* indices;  // 3 per triangle
  uint32_t triangles;
};

constexpr uint32_t KD_NO_HIT = 0xffffffffu;
struct MeshHit {
  float t;            // distance in units of |d|
  uint32_t triangle;  // KD_NO_HIT: none
};

// Moller-Trumbore; true with t when the ray meets triangle (a, b, c) at t > 0.
GVDP_HD GVDP_INLINE bool intersectTriangle(const Ray& r, Vec3f a, Vec3f b, Vec3f c, float& t) {
  Vec3f e1 = b - a, e2 = c - a;
  Vec3f p = cross(r.d, e2);
  float det = dot(e1, p);
  if (det == 0.0f) return false;
  float inv = 1.0f / det;
  Vec3f s = r.o - a;
  float u = dot(s, p) * inv;
  if (u < 0.0f || u > 1.0f) return false;
  Vec3f q = cross(s, e1);
  float v = dot(r.d, q) * inv;
  if (v < 0.0f || u + v > 1.0f) return false;
  t = dot(e2, q) * inv;
  return t > 0.0f;
}

// Keeps the nearer hit; equal distances keep the lower triangle id (both casts agree on ties).
GVDP_HD GVDP_INLINE void testTriangle(const Ray& r, MeshView mesh, uint32_t tri, MeshHit& best) {
  float t;
  const uint32_t* i = mesh.indices + 3 * tri;
  if (intersectTriangle(r, mesh.vertices[i[0]], mesh.vertices[i[1]], mesh.vertices[i[2]], t) &&
      (t < best.t || (t == best.t && tri < best.triangle)))
    best = {t, tri};
}

GVDP_HD GVDP_INLINE MeshHit closestHitBruteForce(const Ray& r, MeshView mesh) {
  MeshHit best{std::numeric_limits<float>::infinity(), KD_NO_HIT};
  for (uint32_t tri = 0; tri < mesh.triangles; ++tri) testTriangle(r, mesh, tri, best);
  return best;
}

// The ray's interval inside a box (slab test); false when it misses. The far distance grows by
// 2 gamma(3) (pbrt-v3 3.9.2: the rounding bound of the slab distances), so a ray that enters
// exactly at an edge or corner, whose rounded entry can pass its rounded exit by an ulp, is kept.
constexpr float KD_SLAB_GROWTH =
    1.0f + 2.0f * (3.0f * 5.96046448e-8f) / (1.0f - 3.0f * 5.96046448e-8f);
GVDP_HD GVDP_INLINE bool rayBoxInterval(const Ray& r, Vec3f invD, Box3f b, float& t0, float& t1) {
  t0 = 0.0f;
  t1 = std::numeric_limits<float>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    float o = component(r.o, axis), inv = component(invD, axis);
    float a = (component(b.lo, axis) - o) * inv, c = (component(b.hi, axis) - o) * inv;
    if (a > c) {
      float s = a;
      a = c;
      c = s;
    }
    // NaN (a zero direction on a face plane) leaves the interval as it is
    c = c * KD_SLAB_GROWTH;
    t0 = a > t0 ? a : t0;
    t1 = c < t1 ? c : t1;
    if (t0 > t1) return false;
  }
  return true;
}

GVDP_HD GVDP_INLINE MeshHit closestHit(const Ray& r, KdTreeView tree, MeshView mesh) {
  MeshHit best{std::numeric_limits<float>::infinity(), KD_NO_HIT};
  Vec3f invD = inverseDirection(r);
  float tMin, tMax;
  if (!rayBoxInterval(r, invD, tree.bounds, tMin, tMax)) return best;
  struct Pending {
    uint32_t node;
    float tMin, tMax;
  } stack[KD_STACK_SIZE];
  int top = 0;
  uint32_t node = 0;
  for (;;) {
    KdNode n = tree.nodes[node];
    while (!isLeaf(n)) {
      int axis = splitAxis(n);
      float split = splitPosition(n), o = component(r.o, axis);
      float tSplit = (split - o) * component(invD, axis);
      bool belowFirst = o < split || (o == split && component(r.d, axis) <= 0.0f);
      uint32_t first = belowFirst ? leftChild(n) : rightChild(n);
      uint32_t second = belowFirst ? rightChild(n) : leftChild(n);
      if (tSplit != tSplit) {  // NaN: the ray lies in the plane; both children, whole interval
        stack[top++] = {second, tMin, tMax};
        node = first;
      } else if (tSplit > tMax || tSplit <= 0.0f) {
        node = first;
      } else if (tSplit < tMin) {
        node = second;
      } else {  // both, near first
        stack[top++] = {second, tSplit, tMax};
        node = first;
        tMax = tSplit;
      }
      n = tree.nodes[node];
    }
    uint32_t first = leafFirst(n);
    for (uint32_t k = 0; k < leafCount(n); ++k)
      testTriangle(r, mesh, tree.leafTriangles[first + k], best);
    if (best.t <= tMax || top == 0) break;
    --top;
    node = stack[top].node;
    tMin = stack[top].tMin;
    tMax = stack[top].tMax;
  }
  return best;
}

}  // namespace gvdp::detail
