// The full-SAH kd-tree (mesh/kdtree*.h): its rules in isolation, the invariants of built trees
// (checked against brute-force recomputation of every node's split), ray casts against brute
// force over all triangles, determinism, and the `gvdp kdtree` / `gvdp mesh` command lines.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <set>

#include "gvdp/base/parallel.h"
#include "gvdp/mesh/kdtree_build.h"
#include "gvdp/mesh/kdtree_raycast.h"
#include "gvdp/mesh/kdtree_stats.h"
#include "gvdp/mesh/mesh_io.h"
#include "mesh_test_util.h"
#include "test_util.h"

namespace gvdp::detail {
namespace {

struct Named {
  const char* name;
  Mesh mesh;
};

std::vector<Named> testMeshes() {
  std::vector<Named> m;
  m.push_back({"cube", test::cubeMesh()});  // a leaf: no candidate inside its box
  m.push_back({"subdivided cube", subdivide(test::cubeMesh(), 3)});  // many coplanar flats
  m.push_back({"stacked squares", test::stackedSquares()});
  m.push_back({"icosphere", test::icosphere(3)});
  m.push_back({"soup", test::randomSoup(3000, 0.1f, 7)});
  m.push_back({"large soup", test::randomSoup(800, 0.6f, 11)});
  return m;
}

// The counts of kdtree.h straight from the definition.
KdSplit bruteBestSplit(const std::vector<Box3f>& boxes, const std::vector<uint32_t>& tris,
                       Box3f box) {
  KdSplit best = noSplit();
  for (int axis = 0; axis < 3; ++axis) {
    std::set<float> positions;
    for (uint32_t t : tris) {
      positions.insert(component(boxes[t].lo, axis));
      positions.insert(component(boxes[t].hi, axis));
    }
    for (float p : positions) {
      uint32_t left = 0, right = 0;
      for (uint32_t t : tris) {
        float lo = component(boxes[t].lo, axis), hi = component(boxes[t].hi, axis);
        left += lo < p || (lo == p && hi == p);
        right += hi > p;
      }
      KdSplit s = evaluateSplit(box, axis, p, left, right);
      if (betterSplit(s, best)) best = s;
    }
  }
  return best;
}

// Does a triangle's box touch a leaf's box (open overlap, or flat inside the closed slab)?
bool touches(Box3f t, Box3f leaf) {
  for (int a = 0; a < 3; ++a) {
    float lo = component(t.lo, a), hi = component(t.hi, a);
    float blo = component(leaf.lo, a), bhi = component(leaf.hi, a);
    bool open = lo < bhi && hi > blo;
    bool flatInside = lo == hi && blo <= lo && lo <= bhi;
    if (!open && !flatInside) return false;
  }
  return true;
}

// Walks the tree: every node's triangles (the union of its leaves) split exactly as kdtree.h
// assigns them, the split is the brute-force best, the leaf rule holds, and every triangle is in
// every leaf it touches. Returns the triangles under `node`.
std::vector<uint32_t> checkNode(const KdTree& tree, const std::vector<Box3f>& boxes, uint32_t node,
                                Box3f box, int depth, int& leaves, bool checkSah, int& flatSplits) {
  KdNode n = tree.nodes[node];
  if (isLeaf(n)) {
    ++leaves;
    std::vector<uint32_t> tris(tree.leafTriangles.begin() + leafFirst(n),
                               tree.leafTriangles.begin() + leafFirst(n) + leafCount(n));
    EXPECT_TRUE(std::is_sorted(tris.begin(), tris.end()));
    for (uint32_t t = 0; t < boxes.size(); ++t) {
      bool in = std::binary_search(tris.begin(), tris.end(), t);
      EXPECT_TRUE(in || !touches(boxes[t], box)) << "triangle " << t << " missing from a leaf";
    }
    if (checkSah) {
      KdSplit best = bruteBestSplit(boxes, tris, box);
      EXPECT_FALSE(shouldSplit(box, leafCount(n), depth, best)) << "a leaf that should split";
    }
    return tris;
  }
  int axis = splitAxis(n);
  float p = splitPosition(n);
  EXPECT_LT(component(box.lo, axis), p);  // the children partition the box at p
  EXPECT_LT(p, component(box.hi, axis));
  std::vector<uint32_t> left = checkNode(tree, boxes, leftChild(n), leftBox(box, axis, p),
                                         depth + 1, leaves, checkSah, flatSplits);
  std::vector<uint32_t> right = checkNode(tree, boxes, rightChild(n), rightBox(box, axis, p),
                                          depth + 1, leaves, checkSah, flatSplits);
  std::vector<uint32_t> all;
  std::set_union(left.begin(), left.end(), right.begin(), right.end(), std::back_inserter(all));
  std::vector<uint32_t> wantLeft, wantRight;
  for (uint32_t t : all) {
    float lo = component(boxes[t].lo, axis), hi = component(boxes[t].hi, axis);
    bool flatHere = lo == p && hi == p;
    flatSplits += flatHere;
    if (lo < p || flatHere) wantLeft.push_back(t);
    if (hi > p || flatHere) wantRight.push_back(t);
  }
  EXPECT_EQ(std::set<uint32_t>(left.begin(), left.end()),
            std::set<uint32_t>(wantLeft.begin(), wantLeft.end()));
  EXPECT_EQ(std::set<uint32_t>(right.begin(), right.end()),
            std::set<uint32_t>(wantRight.begin(), wantRight.end()));
  if (checkSah) {
    KdSplit best = bruteBestSplit(boxes, all, box);
    EXPECT_TRUE(shouldSplit(box, static_cast<uint32_t>(all.size()), depth, best));
    EXPECT_EQ(best.axis, axis);
    EXPECT_EQ(floatBits(best.pos), floatBits(p));
  }
  return all;
}

std::vector<Ray> randomRays(Box3f box, int count, uint32_t seed, bool axisAligned) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Vec3f c = (box.lo + box.hi) * 0.5f, size = box.hi - box.lo;
  float radius = length(size);
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    Vec3f target = box.lo + Vec3f{u(rng), u(rng), u(rng)} * size;
    if (axisAligned) {  // zero direction components: the traversal's infinite and NaN cases
      int a = i % 3;
      Vec3f d{0.0f, 0.0f, 0.0f};
      setComponent(d, a, i % 2 ? 1.0f : -1.0f);
      rays.push_back({target - d * radius, d});
      continue;
    }
    Vec3f o = c + normalize(Vec3f{u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f}) * radius;
    rays.push_back({o, normalize(target - o)});
  }
  return rays;
}

}  // namespace

TEST(KdTree, EventOrderSplitOrderAndSides) {
  KdEvent end = kdEvent(1.0f, 9, KD_EVENT_END), planar = kdEvent(1.0f, 5, KD_EVENT_PLANAR);
  KdEvent start = kdEvent(1.0f, 1, KD_EVENT_START), before = kdEvent(0.5f, 20, KD_EVENT_START);
  EXPECT_TRUE(kdEventLess(end, planar));
  EXPECT_TRUE(kdEventLess(planar, start));
  EXPECT_TRUE(kdEventLess(before, end));
  EXPECT_TRUE(kdEventLess(kdEvent(-2.0f, 3, KD_EVENT_END), kdEvent(-1.0f, 3, KD_EVENT_END)));
  EXPECT_TRUE(kdEventLess(kdEvent(1.0f, 3, KD_EVENT_END), kdEvent(1.0f, 4, KD_EVENT_END)));
  EXPECT_EQ(eventKey(kdEvent(-0.0f, 0, KD_EVENT_END)), eventKey(kdEvent(0.0f, 0, KD_EVENT_END)));
  EXPECT_EQ(eventTriangle(planar), 5u);
  // sides: a START left of p says left, an END right of p says right, a PLANAR at p both
  EXPECT_EQ(eventSides(kdEvent(0.5f, 0, KD_EVENT_START), 1.0f), KD_LEFT);
  EXPECT_EQ(eventSides(kdEvent(1.0f, 0, KD_EVENT_START), 1.0f), 0u);
  EXPECT_EQ(eventSides(kdEvent(1.0f, 0, KD_EVENT_END), 1.0f), 0u);
  EXPECT_EQ(eventSides(kdEvent(1.5f, 0, KD_EVENT_END), 1.0f), KD_RIGHT);
  EXPECT_EQ(eventSides(kdEvent(1.0f, 0, KD_EVENT_PLANAR), 1.0f), KD_LEFT | KD_RIGHT);
  // ties: lower cost, then axis x < y < z, then lower position; "none" loses to everything
  KdSplit a{10.0f, 1, 0.5f, 0, 0}, b{10.0f, 0, 0.7f, 0, 0}, c{10.0f, 0, 0.6f, 0, 0};
  EXPECT_TRUE(betterSplit(b, a));
  EXPECT_TRUE(betterSplit(c, b));
  EXPECT_TRUE(betterSplit(KdSplit{9.0f, 2, 0.9f, 0, 0}, c));
  EXPECT_TRUE(betterSplit(a, noSplit()));
  // the cost: C_T + C_I (A_L n_L + A_R n_R) / A; a unit cube cut in half, 4 and 6 triangles
  Box3f unit{{0, 0, 0}, {1, 1, 1}};
  EXPECT_EQ(sahSplitCost(unit, 0, 0.5f, 4, 6), 15.0f + 20.0f * (2.0f * 4 + 2.0f * 6) / 3.0f);
  EXPECT_FALSE(evaluateSplit(unit, 0, 1.0f, 1, 0).axis >= 0);  // on the box's face: no candidate
  // nodes round-trip
  KdNode in = kdInterior(2, -0.25f, 77), leaf = kdLeaf(123, 4);
  EXPECT_FALSE(isLeaf(in));
  EXPECT_EQ(splitAxis(in), 2);
  EXPECT_EQ(splitPosition(in), -0.25f);
  EXPECT_EQ(leftChild(in), 77u);
  EXPECT_EQ(rightChild(in), 78u);
  EXPECT_TRUE(isLeaf(leaf));
  EXPECT_EQ(leafFirst(leaf), 123u);
  EXPECT_EQ(leafCount(leaf), 4u);
}

// Small meshes: the whole tree against the definition, node by node (brute-force SAH).
TEST(KdTree, EveryNodeIsTheBruteForceBestSplitAndLeavesHoldWhatTheyTouch) {
  std::vector<Named> meshes;
  meshes.push_back({"cube", test::cubeMesh()});
  meshes.push_back({"subdivided cube", subdivide(test::cubeMesh(), 2)});
  meshes.push_back({"icosphere", test::icosphere(2)});
  meshes.push_back({"soup", test::randomSoup(400, 0.15f, 3)});
  for (const Named& m : meshes) {
    SCOPED_TRACE(m.name);
    KdTree tree = buildKdTreeSequential(m.mesh);
    std::vector<Box3f> boxes = kdTriangleBoxes(m.mesh);
    int leaves = 0, flatSplits = 0;
    std::vector<uint32_t> all = checkNode(tree, boxes, 0, tree.bounds, 0, leaves, true, flatSplits);
    EXPECT_EQ(all.size(), m.mesh.triangleCount());
    KdTreeStats s = kdTreeStats(tree);
    EXPECT_EQ(s.leaves, static_cast<size_t>(leaves));
    EXPECT_EQ(s.nodes, 2 * s.leaves - 1);
    EXPECT_EQ(s.nodes, tree.nodes.size());
    if (m.mesh.triangleCount() > 12) {
      EXPECT_GT(s.leaves, 1u) << "nothing was split";
    }
    if (std::string(m.name) == "stacked squares") {
      EXPECT_GT(flatSplits, 0) << "no flat triangle lay in a split plane: the rule is untested";
    }
  }
}

// Larger meshes: the structural invariants only (no brute-force SAH).
TEST(KdTree, InvariantsOnLargerMeshes) {
  for (const Named& m : testMeshes()) {
    SCOPED_TRACE(m.name);
    KdTree tree = buildKdTreeSequential(m.mesh);
    std::vector<Box3f> boxes = kdTriangleBoxes(m.mesh);
    int leaves = 0, flatSplits = 0;
    EXPECT_EQ(checkNode(tree, boxes, 0, tree.bounds, 0, leaves, false, flatSplits).size(),
              m.mesh.triangleCount());
    KdTreeStats s = kdTreeStats(tree);
    EXPECT_LE(s.maxDepth, KD_MAX_DEPTH);
    // the SAH cost of the tree is below that of one leaf holding everything
    EXPECT_LE(s.sahCost, KD_COST_INTERSECTION * static_cast<double>(m.mesh.triangleCount()));
  }
}

TEST(KdTree, RayCastsEqualBruteForceOverAllTriangles) {
  for (const Named& m : testMeshes()) {
    SCOPED_TRACE(m.name);
    KdTree tree = buildKdTreeSequential(m.mesh);
    MeshView mv{m.mesh.vertices.data(), m.mesh.indices.data(),
                static_cast<uint32_t>(m.mesh.triangleCount())};
    for (bool axisAligned : {false, true}) {
      std::vector<Ray> rays = randomRays(tree.bounds, axisAligned ? 3000 : 20000, 5, axisAligned);
      std::vector<MeshHit> kd(rays.size()), brute(rays.size());
      parallelFor(static_cast<int64_t>(rays.size()), [&](int64_t i) {
        kd[i] = closestHit(rays[i], tree.view(), mv);
        brute[i] = closestHitBruteForce(rays[i], mv);
      });
      int hits = 0, bad = 0;
      for (size_t i = 0; i < rays.size() && bad < 5; ++i) {
        bool same = kd[i].triangle == brute[i].triangle;
        if (brute[i].triangle != KD_NO_HIT) {
          ++hits;
          same =
              kd[i].triangle != KD_NO_HIT && std::fabs(kd[i].t - brute[i].t) <= 1e-5f * brute[i].t;
          // a different triangle only on a tie (a shared edge): the same distance
        }
        if (!same) {
          ++bad;
          ADD_FAILURE() << "ray " << i << ": kd " << kd[i].triangle << " at " << kd[i].t
                        << ", brute " << brute[i].triangle << " at " << brute[i].t;
        }
      }
      EXPECT_GT(hits, static_cast<int>(rays.size()) / 20) << "too few rays hit to test much";
      size_t sameId = 0;
      for (size_t i = 0; i < rays.size(); ++i) sameId += kd[i].triangle == brute[i].triangle;
      EXPECT_GE(sameId, rays.size() - rays.size() / 1000) << "ties on shared edges only";
    }
  }
}

TEST(KdTree, BuildsAreDeterministicAndSameTreeSeesDifferences) {
  for (const Named& m : testMeshes()) {
    SCOPED_TRACE(m.name);
    KdTree a = buildKdTreeSequential(m.mesh), b = buildKdTreeSequential(m.mesh);
    std::string why;
    EXPECT_TRUE(sameTree(a, b, &why)) << why;
    if (isLeaf(b.nodes[0])) continue;  // the cube
    KdTree c = b;                      // another split position at the root's left child's subtree
    c.nodes[0].payload = floatBits(splitPosition(c.nodes[0]) + 1e-3f);
    EXPECT_FALSE(sameTree(a, c, &why));
    EXPECT_NE(why.find("the root"), std::string::npos) << why;
    // the same tree stored in another order is the same tree: swap the root's children
    KdTree d = b;
    uint32_t l = leftChild(d.nodes[0]);
    KdNode left = d.nodes[l], right = d.nodes[l + 1];
    // relocate: append both children in swapped storage slots (right first)
    auto at = static_cast<uint32_t>(d.nodes.size());
    d.nodes.push_back(left);
    d.nodes.push_back(right);
    d.nodes[0] = kdInterior(splitAxis(d.nodes[0]), splitPosition(d.nodes[0]), at);
    EXPECT_TRUE(sameTree(a, d, &why)) << why;
  }
}

// Seed 004's level-by-level builder makes the sequential builder's tree, node for node, whatever
// the number of threads (the pool) and however the nodes are stored (level by level here).
TEST(KdTree, LevelByLevelBuilderMakesTheSequentialTree) {
  std::vector<Named> meshes = testMeshes();
  meshes.push_back({"icosphere 4", test::icosphere(4)});
  meshes.push_back({"dense soup", test::randomSoup(20000, 0.05f, 13)});
  for (const Named& m : meshes) {
    SCOPED_TRACE(m.name);
    KdTree seq = buildKdTreeSequential(m.mesh), par = buildKdTreeParallel(m.mesh);
    std::string why;
    EXPECT_TRUE(sameTree(seq, par, &why)) << why;
    EXPECT_EQ(par.nodes.size(), seq.nodes.size());
    EXPECT_EQ(par.leafTriangles.size(), seq.leafTriangles.size());
    EXPECT_DOUBLE_EQ(kdTreeStats(par).sahCost, kdTreeStats(seq).sahCost);
  }
}

// The per-event rule of the level-by-level builder against the sequential sweep's counts: every
// candidate of a node with ties (several END, PLANAR and START events at one position).
TEST(KdTree, PerEventRuleEvaluatesEachPositionOnceWithTheSweepsCounts) {
  // triangles' extents on one axis: [0,1] [1,2] [1,1] [1,1] [1,3] [2,2] [0,2]
  const float lo[] = {0, 1, 1, 1, 1, 2, 0}, hi[] = {1, 2, 1, 1, 3, 2, 2};
  std::vector<KdEvent> ev;
  for (uint32_t t = 0; t < 7; ++t) {
    if (lo[t] == hi[t]) {
      ev.push_back(kdEvent(lo[t], t, KD_EVENT_PLANAR));
    } else {
      ev.push_back(kdEvent(lo[t], t, KD_EVENT_START));
      ev.push_back(kdEvent(hi[t], t, KD_EVENT_END));
    }
  }
  std::sort(ev.begin(), ev.end(), kdEventLess);
  Box3f box{{-1, 0, 0}, {4, 1, 1}};
  KdEventCounts before{0, 0, 0};
  std::vector<KdSplit> found;
  for (uint32_t i = 0; i < ev.size(); ++i) {
    KdSplit s = evaluateEvent(ev.data(), i, 0, static_cast<uint32_t>(ev.size()), before, 7, box, 0);
    if (s.axis >= 0) found.push_back(s);
    before = before + countsOf(ev[i]);
  }
  // positions 0, 1, 2, 3 once each; left = min < p or flat at p, right = max > p
  ASSERT_EQ(found.size(), 4u);
  const uint32_t wantLeft[] = {0, 4, 7, 7}, wantRight[] = {7, 4, 1, 0};
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(found[k].pos, static_cast<float>(k));
    EXPECT_EQ(found[k].left, wantLeft[k]) << "at " << k;
    EXPECT_EQ(found[k].right, wantRight[k]) << "at " << k;
  }
}

TEST(KdTreeCli, BadInputIsOneLineWithStatus2AndAGoodRunPrintsTheTree) {
  std::string d = test::tempDir("kdtree_cli");
  std::filesystem::create_directories(d);
  std::string cube = d + "/cube.ply";
  writePly(test::cubeMesh(), cube);
  auto expectInputError = [](const std::string& args, const std::string& mentions) {
    test::CommandResult r = test::runGvdp(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("gvdp: error:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(mentions), std::string::npos) << args << "\n" << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << "one line: " << r.output;
  };
  expectInputError("kdtree --mesh " + d + "/missing.off", d + "/missing.off: cannot open");
  expectInputError("kdtree --mesh " + d + "/cube.stl", "unknown mesh format");
  expectInputError("kdtree --mesh " + cube + " --repeat 0", "--repeat 0");
  expectInputError("kdtree --mesh " + cube + " --rays -4", "--rays -4");
  expectInputError("kdtree --mesh " + cube + " --repeat lots", "lots");
  expectInputError("kdtree --mesh " + cube + " --builders magic", "'magic'");
  expectInputError("kdtree", "--mesh");
  expectInputError("mesh subdivide --times 0 " + cube + " " + d + "/out.ply", "--times 0");
  expectInputError("mesh subdivide --times 2 " + cube + " " + d + "/out.off", "must be a .ply");
  expectInputError("mesh subdivide " + cube, "out");
  expectInputError("mesh frobnicate", "'frobnicate'");
  expectInputError("mesh", "subdivide");
  expectInputError("mesh sphere --times 9 " + d + "/sphere.ply", "--times 9");
  expectInputError("mesh sphere --times 2 " + d + "/sphere.off", "must be a .ply");
  test::CommandResult sphere = test::runGvdp("mesh sphere --times 2 " + d + "/sphere.ply");
  ASSERT_EQ(sphere.status, 0) << sphere.output;
  Mesh icosphere = readMesh(d + "/sphere.ply");
  EXPECT_EQ(icosphere.triangleCount(), 20u * 16u);
  EXPECT_TRUE(test::isClosed(icosphere));

  test::CommandResult sub =
      test::runGvdp("mesh subdivide --times 2 " + cube + " " + d + "/cube16.ply");
  ASSERT_EQ(sub.status, 0) << sub.output;
  EXPECT_EQ(readMesh(d + "/cube16.ply").triangleCount(), 12u * 16u);
  test::CommandResult r = test::runGvdp("kdtree --mesh " + d + "/cube16.ply --repeat 2 --rays 500");
  ASSERT_EQ(r.status, 0) << r.output;
  KdTreeStats s = kdTreeStats(buildKdTreeSequential([&] {
    Mesh m = readMesh(d + "/cube16.ply");
    placeMesh(m);
    return m;
  }()));
  EXPECT_NE(r.output.find("192 triangles"), std::string::npos) << r.output;
  EXPECT_NE(
      r.output.find(std::to_string(s.nodes) + " nodes, " + std::to_string(s.leaves) + " leaves"),
      std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("500 through the box"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("level-by-level build"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the same tree as the sequential builder's"), std::string::npos)
      << r.output;
}

}  // namespace gvdp::detail
