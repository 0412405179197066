// Queries on a mesh's surface, GVDP_HD over PODs: the triangle nearest to a point with the
// feature (face, edge, vertex) its nearest point lies on, the signed distance that feature's
// pseudonormal gives (mesh_normals.h), whether any triangle's box meets a box (both through the
// distance hierarchy, mesh_bvh.h), and inside or outside by a ray cast (through the kd-tree).
// Nearest: the nearer child first, with a stack of far children and their squared distance lower
// bounds (their boxes'); a node is skipped when its bound is not below the best so far. Ties
// between equally near triangles keep the first found: a query's answer depends on the point
// alone.
#pragma once

#include <cstdint>

#include "gvdp/mesh/kdtree.h"
#include "gvdp/mesh/kdtree_raycast.h"
#include "gvdp/mesh/mesh_bvh.h"

namespace gvdp::detail {

// A mesh's surface in memory it does not own: vertices, triangles, the kd-tree, the normals and
// the distance hierarchy.
struct SurfaceView {
  MeshView mesh;
  KdTreeView tree;
  const Vec3f* vertexNormals;  // one per vertex
  const Vec3f* edgeNormals;    // three per triangle
  MeshBvhView bvh;
};

// Where on a triangle its nearest point lies.
enum class TriangleFeature : uint8_t { Face, Vertex0, Vertex1, Vertex2, Edge0, Edge1, Edge2 };

struct NearestPoint {
  Vec3f point;
  float b1, b2;  // barycentric weights of corners 1 and 2 (corner 0: 1 - b1 - b2)
  TriangleFeature feature;
};

// Ericson, "Real-Time Collision Detection" 5.1.5, with the Voronoi region it ends in. Edge k runs
// from corner k to corner k + 1.
GVDP_HD GVDP_INLINE NearestPoint nearestOnTriangle(Vec3f p, Vec3f a, Vec3f b, Vec3f c) {
  Vec3f ab = b - a, ac = c - a, ap = p - a;
  float d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return {a, 0.0f, 0.0f, TriangleFeature::Vertex0};
  Vec3f bp = p - b;
  float d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return {b, 1.0f, 0.0f, TriangleFeature::Vertex1};
  float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
    float v = d1 / (d1 - d3);
    return {a + ab * v, v, 0.0f, TriangleFeature::Edge0};
  }
  Vec3f cp = p - c;
  float d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return {c, 0.0f, 1.0f, TriangleFeature::Vertex2};
  float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
    float w = d2 / (d2 - d6);
    return {a + ac * w, 0.0f, w, TriangleFeature::Edge2};
  }
  float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
    float w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {b + (c - b) * w, 1.0f - w, w, TriangleFeature::Edge1};
  }
  float sum = va + vb + vc;
  if (!(sum > 0.0f)) return {a, 0.0f, 0.0f, TriangleFeature::Vertex0};  // degenerate
  float v = vb / sum, w = vc / sum;
  return {a + ab * v + ac * w, v, w, TriangleFeature::Face};
}

struct NearestTriangle {
  float distanceSq;   // the reach asked for when none within it
  uint32_t triangle;  // KD_NO_HIT: none, or a surfel
  NearestPoint at;
  uint32_t surfel = KD_NO_HIT;  // the hierarchy's node whose surfel stood in, if any

  GVDP_HD bool found() const { return triangle != KD_NO_HIT || surfel != KD_NO_HIT; }
};

// The point of a surfel's disc (radius: half its width) nearest to p.
GVDP_HD GVDP_INLINE Vec3f nearestOnSurfel(Vec3f p, const MeshBvhNode& s) {
  Vec3f w = p - s.centre;
  Vec3f lateral = w - s.normal * dot(w, s.normal);
  float l = length(lateral), r = 0.5f * surfelWidth(s);
  return s.centre + (l > r ? lateral * (r / l) : lateral);
}

// The squared distance from p to a box (0 inside).
GVDP_HD GVDP_INLINE float boxDistanceSq(Vec3f p, Box3f b) {
  float dx = fmaxf(fmaxf(b.lo.x - p.x, p.x - b.hi.x), 0.0f);
  float dy = fmaxf(fmaxf(b.lo.y - p.y, p.y - b.hi.y), 0.0f);
  float dz = fmaxf(fmaxf(b.lo.z - p.z, p.z - b.hi.z), 0.0f);
  return dx * dx + dy * dy + dz * dz;
}

// The triangle nearest to p among those closer than sqrt(reachSq); a node whose box is at most
// `surfelAt` wide answers with its surfel (0: triangles only, the exact nearest).
GVDP_HD GVDP_INLINE NearestTriangle nearestTriangle(Vec3f p, const SurfaceView& s, float reachSq,
                                                    float surfelAt = 0.0f) {
  NearestTriangle best{reachSq, KD_NO_HIT, {}};
  const MeshBvhNode* nodes = s.bvh.nodes;
  if (!(boxDistanceSq(p, nodes[0].box) < best.distanceSq)) return best;
  struct Pending {
    uint32_t node;
    float boundSq;
  } stack[MESH_BVH_STACK];
  int top = 0;
  uint32_t node = 0;
  for (;;) {
    const MeshBvhNode& n = nodes[node];
    if (surfelAt > 0.0f && surfelWidth(n) <= surfelAt) {
      Vec3f q = nearestOnSurfel(p, n);
      Vec3f d = p - q;
      float dSq = dot(d, d);
      if (dSq < best.distanceSq) best = {dSq, KD_NO_HIT, {q, 0.0f, 0.0f, {}}, node};
    } else if (n.count == 0) {
      float left = boxDistanceSq(p, nodes[n.first].box);
      float right = boxDistanceSq(p, nodes[n.first + 1].box);
      bool leftFirst = left <= right;
      float nearSq = leftFirst ? left : right, farSq = leftFirst ? right : left;
      if (farSq < best.distanceSq) stack[top++] = {leftFirst ? n.first + 1 : n.first, farSq};
      if (nearSq < best.distanceSq) {
        node = leftFirst ? n.first : n.first + 1;
        continue;
      }
    } else {
      for (uint32_t k = 0; k < n.count; ++k) {
        uint32_t tri = s.bvh.triangles[n.first + k];
        const uint32_t* i = s.mesh.indices + 3 * tri;
        NearestPoint q = nearestOnTriangle(p, s.mesh.vertices[i[0]], s.mesh.vertices[i[1]],
                                           s.mesh.vertices[i[2]]);
        Vec3f d = p - q.point;
        float dSq = dot(d, d);
        if (dSq < best.distanceSq) best = {dSq, tri, q};
      }
    }
    do {
      if (top == 0) return best;
      --top;
    } while (!(stack[top].boundSq < best.distanceSq));
    node = stack[top].node;
  }
}

// The pseudonormal of the feature a nearest point lies on (a surfel's normal, or where that
// cancelled, the direction from its centre).
GVDP_HD GVDP_INLINE Vec3f featureNormal(const SurfaceView& s, const NearestTriangle& t, Vec3f p) {
  if (t.surfel != KD_NO_HIT) {
    const MeshBvhNode& k = s.bvh.nodes[t.surfel];
    return k.normal.x != 0.0f || k.normal.y != 0.0f || k.normal.z != 0.0f ? k.normal : p - k.centre;
  }
  const uint32_t* i = s.mesh.indices + 3 * t.triangle;
  switch (t.at.feature) {
    case TriangleFeature::Vertex0:
      return s.vertexNormals[i[0]];
    case TriangleFeature::Vertex1:
      return s.vertexNormals[i[1]];
    case TriangleFeature::Vertex2:
      return s.vertexNormals[i[2]];
    case TriangleFeature::Edge0:
      return s.edgeNormals[3 * t.triangle];
    case TriangleFeature::Edge1:
      return s.edgeNormals[3 * t.triangle + 1];
    case TriangleFeature::Edge2:
      return s.edgeNormals[3 * t.triangle + 2];
    default: {
      Vec3f a = s.mesh.vertices[i[0]];
      return cross(s.mesh.vertices[i[1]] - a, s.mesh.vertices[i[2]] - a);
    }
  }
}

// The shading normal at a point of a triangle: the vertex normals interpolated.
GVDP_HD GVDP_INLINE Vec3f shadingNormal(const SurfaceView& s, uint32_t triangle, float b1,
                                        float b2) {
  const uint32_t* i = s.mesh.indices + 3 * triangle;
  Vec3f n = s.vertexNormals[i[0]] * (1.0f - b1 - b2) + s.vertexNormals[i[1]] * b1 +
            s.vertexNormals[i[2]] * b2;
  float l = length(n);
  return l > 0.0f ? n / l : Vec3f{0.0f, 1.0f, 0.0f};
}

// Whether p is inside the surface, by the pseudonormal of its nearest feature (exact for a
// closed, consistently oriented mesh, whatever the distance).
GVDP_HD GVDP_INLINE bool insideOf(Vec3f p, const SurfaceView& s, const NearestTriangle& t) {
  return t.found() && dot(p - t.at.point, featureNormal(s, t, p)) < 0.0f;
}

// The shading normal at a nearest point: interpolated on a triangle, a surfel's own.
GVDP_HD GVDP_INLINE Vec3f shadingNormal(const SurfaceView& s, const NearestTriangle& t, Vec3f p) {
  if (t.surfel != KD_NO_HIT) return normalize(featureNormal(s, t, p));
  return shadingNormal(s, t.triangle, t.at.b1, t.at.b2);
}

// Whether p is inside the surface, by a ray cast from it (for points far from the surface, where
// a nearest-triangle query would visit much of the tree): the first triangle a ray meets is
// crossed from the inside when the ray leaves through its front (a closed, consistently oriented
// mesh); no triangle: outside. A grazing first hit (|cos| < 0.1 with the face) tells little, so
// the next of three fixed directions (not axis-aligned: no ray in a split plane) is tried.
GVDP_HD GVDP_INLINE bool insideByRay(Vec3f p, const SurfaceView& s) {
  const Vec3f DIRECTIONS[3] = {{0.5773503f, 0.6172134f, 0.5345225f},
                               {-0.7071068f, 0.4082483f, -0.5773503f},
                               {0.3015113f, -0.9045340f, 0.3015113f}};
  bool inside = false;
  for (const Vec3f& d : DIRECTIONS) {
    MeshHit hit = closestHit({p, d}, s.tree, s.mesh);
    if (hit.triangle == KD_NO_HIT) return false;
    const uint32_t* i = s.mesh.indices + 3 * hit.triangle;
    Vec3f a = s.mesh.vertices[i[0]];
    Vec3f n = cross(s.mesh.vertices[i[1]] - a, s.mesh.vertices[i[2]] - a);
    float cosine = dot(n, d), norm = length(n);
    inside = cosine > 0.0f;
    if (fabsf(cosine) > 0.1f * norm) break;
  }
  return inside;
}

// Whether the box of some triangle meets `query` (closed boxes).
GVDP_HD GVDP_INLINE bool anyTriangleBoxMeets(Box3f query, const SurfaceView& s) {
  const MeshBvhNode* nodes = s.bvh.nodes;
  if (!boxesMeet(query, nodes[0].box)) return false;
  uint32_t stack[MESH_BVH_STACK];
  int top = 0;
  uint32_t node = 0;
  for (;;) {
    const MeshBvhNode& n = nodes[node];
    if (n.count == 0) {  // both children's boxes are tested before descending
      bool left = boxesMeet(query, nodes[n.first].box);
      bool right = boxesMeet(query, nodes[n.first + 1].box);
      if (left && right) stack[top++] = n.first + 1;
      if (left || right) {
        node = left ? n.first : n.first + 1;
        continue;
      }
    } else {
      for (uint32_t k = 0; k < n.count; ++k) {
        const uint32_t* i = s.mesh.indices + 3 * s.bvh.triangles[n.first + k];
        Vec3f a = s.mesh.vertices[i[0]], b = s.mesh.vertices[i[1]], c = s.mesh.vertices[i[2]];
        if (boxesMeet(query, triangleBox(a, b, c))) return true;
      }
    }
    if (top == 0) return false;
    node = stack[--top];
  }
}

}  // namespace gvdp::detail
