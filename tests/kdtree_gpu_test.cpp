// The GPU kd-tree builder (mesh/kdtree_cuda.cu) against the CPU builders: the same tree node for
// node (sameTree) as the sequential builder's, and, as it makes the level-by-level builder's steps
// in the same order, the same storage as that builder's. Skipped without a CUDA device.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "gvdp/mesh/kdtree_build.h"
#include "gvdp/mesh/kdtree_stats.h"
#include "mesh_test_util.h"
#include "test_util.h"

namespace gvdp::detail {
namespace {

struct Named {
  const char* name;
  Mesh mesh;
};

double msOf(const std::chrono::steady_clock::time_point& start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

bool sameNodes(const KdTree& a, const KdTree& b) {
  return a.nodes.size() == b.nodes.size() &&
         std::equal(a.nodes.begin(), a.nodes.end(), b.nodes.begin(),
                    [](KdNode x, KdNode y) { return x.word == y.word && x.payload == y.payload; });
}

void expectEqualTrees(const KdTree& gpu, const KdTree& seq) {
  std::string why;
  EXPECT_TRUE(sameTree(gpu, seq, &why)) << why;
  KdTreeStats g = kdTreeStats(gpu), s = kdTreeStats(seq);
  EXPECT_EQ(g.nodes, s.nodes);
  EXPECT_EQ(g.leaves, s.leaves);
  EXPECT_EQ(g.emptyLeaves, s.emptyLeaves);
  EXPECT_EQ(g.leafReferences, s.leafReferences);
  EXPECT_EQ(g.maxDepth, s.maxDepth);
  EXPECT_DOUBLE_EQ(g.sahCost, s.sahCost);
  EXPECT_EQ(gpu.leafTriangles.size(), seq.leafTriangles.size());
}

TEST(KdTreeGpu, EqualsTheSequentialTree) {
  GVDP_REQUIRE_GPU();
  // No triangles: the root is an empty leaf (its SAH cost is NaN: only the trees are compared).
  KdTree empty = buildKdTreeCuda(Mesh{});
  EXPECT_TRUE(sameTree(empty, buildKdTreeSequential(Mesh{})));
  EXPECT_TRUE(sameNodes(empty, buildKdTreeParallel(Mesh{})));

  std::vector<Named> meshes;
  meshes.push_back({"cube", test::cubeMesh()});
  meshes.push_back({"subdivided cube", subdivide(test::cubeMesh(), 3)});
  meshes.push_back({"stacked squares", test::stackedSquares()});
  meshes.push_back({"icosphere", test::icosphere(3)});
  meshes.push_back({"icosphere 4", test::icosphere(4)});
  meshes.push_back({"soup", test::randomSoup(3000, 0.1f, 7)});
  meshes.push_back({"large soup", test::randomSoup(800, 0.6f, 11)});
  meshes.push_back({"dense soup", test::randomSoup(20000, 0.05f, 13)});
  for (const Named& m : meshes) {
    SCOPED_TRACE(m.name);
    KdTree seq = buildKdTreeSequential(m.mesh), gpu = buildKdTreeCuda(m.mesh);
    expectEqualTrees(gpu, seq);
    KdTree par = buildKdTreeParallel(m.mesh);
    EXPECT_TRUE(sameNodes(gpu, par)) << "stored unlike the level-by-level builder's tree";
    EXPECT_EQ(gpu.leafTriangles, par.leafTriangles);
  }

  // A larger mesh: an icosphere of 327,680 triangles (20 * 4^7), timed (one warm-up build).
  Mesh large = test::icosphere(7);
  SCOPED_TRACE("icosphere 7");
  buildKdTreeCuda(test::icosphere(2));
  auto start = std::chrono::steady_clock::now();
  KdTree gpu = buildKdTreeCuda(large);
  double gpuMs = msOf(start);
  start = std::chrono::steady_clock::now();
  KdTree seq = buildKdTreeSequential(large);
  double seqMs = msOf(start);
  expectEqualTrees(gpu, seq);
  std::printf("[ measure ] kd-tree of %zu triangles: GPU %.1f ms, sequential %.1f ms (x%.1f)\n",
              large.triangleCount(), gpuMs, seqMs, seqMs / std::max(gpuMs, 1e-3));
}

}  // namespace
}  // namespace gvdp::detail
