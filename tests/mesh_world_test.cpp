// The mesh world (issue 15): nearest-triangle queries and signs against brute force, the
// producer's conservativeness (empty flags and emptyBox), frames of every CPU scheduler equal
// bit for bit, close to the direct renderer and to the ray cast of the triangles (PSNR), and the
// command line's refusals. Meshes are made here (icospheres), never downloaded.
#include <gtest/gtest.h>

#include <random>

#include "gvdp/mesh/mesh_bvh.h"
#include "gvdp/mesh/mesh_io.h"
#include "gvdp/mesh/mesh_normals.h"
#include "gvdp/mesh/surface_queries.h"
#include "gvdp/sched/mesh_scene.h"
#include "mesh_test_util.h"
#include "test_util.h"

namespace gvdp::detail {
namespace {

// Two disjoint spheres of different sizes in one mesh (closed, outward facing).
Mesh twoSpheres() {
  Mesh m = test::icosphere(3), small = test::icosphere(2);
  auto base = static_cast<uint32_t>(m.vertices.size());
  for (Vec3f v : small.vertices) m.vertices.push_back(v * 0.45f + Vec3f{1.6f, 0.3f, 0.2f});
  for (uint32_t i : small.indices) m.indices.push_back(base + i);
  return m;
}

std::string writeTestMesh(const std::string& name) {
  std::string path = test::tempDir(name) + ".ply";
  writePly(twoSpheres(), path);
  return path;
}

float bruteDistanceSq(Vec3f p, const Mesh& m) {
  float best = 3e38f;
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    NearestPoint q = nearestOnTriangle(p, m.corner(t, 0), m.corner(t, 1), m.corner(t, 2));
    best = std::min(best, dot(p - q.point, p - q.point));
  }
  return best;
}

TEST(MeshNearest, DistanceAndSideEqualBruteForceAndTheSpheres) {
  Mesh m = twoSpheres();
  MeshNormals n = meshNormals(m);
  KdTree tree = buildKdTreeSequential(m);
  MeshBvh bvh = buildMeshBvh(m);
  SurfaceView s{{m.vertices.data(), m.indices.data(), static_cast<uint32_t>(m.triangleCount())},
                tree.view(),
                n.vertex.data(),
                n.edge.data(),
                bvh.view()};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.6f, 2.4f);
  int inside = 0;
  for (int i = 0; i < 3000; ++i) {
    Vec3f p{u(rng), u(rng) * 0.8f, u(rng) * 0.8f};
    float brute = bruteDistanceSq(p, m);
    NearestTriangle t = nearestTriangle(p, s, 3e38f);
    ASSERT_NE(t.triangle, KD_NO_HIT);
    EXPECT_EQ(t.distanceSq, brute) << p.x << "," << p.y << "," << p.z;
    // Standing in, a surfel errs by less than its width.
    NearestTriangle coarse = nearestTriangle(p, s, 3e38f, 0.1f);
    EXPECT_NEAR(std::sqrt(coarse.distanceSq), std::sqrt(brute), 0.1f);
    // A bounded query finds it exactly when it lies within the reach.
    EXPECT_EQ(nearestTriangle(p, s, 0.04f).triangle != KD_NO_HIT, brute < 0.04f);
    // The spheres' own inside (polygons lie within 2% inside the unit sphere at 3 subdivisions).
    float big = length(p), smallR = length((p - Vec3f{1.6f, 0.3f, 0.2f}) / 0.45f);
    if (std::abs(big - 1.0f) < 0.03f || std::abs(smallR - 1.0f) < 0.06f) continue;
    bool truth = big < 1.0f || smallR < 1.0f;
    EXPECT_EQ(insideOf(p, s, t), truth) << p.x << "," << p.y << "," << p.z;
    EXPECT_EQ(insideByRay(p, s), truth) << p.x << "," << p.y << "," << p.z;
    inside += truth;
  }
  EXPECT_GT(inside, 200);  // both sides were tested

  // The hierarchy: every triangle in exactly one leaf, a node's box holding its children's; and
  // its box test equals brute force over the triangles' boxes.
  std::vector<int> seen(m.triangleCount(), 0);
  for (const MeshBvhNode& node : bvh.nodes) {
    if (node.count > 0) {
      for (uint32_t k = 0; k < node.count; ++k) ++seen[bvh.triangles[node.first + k]];
      continue;
    }
    for (uint32_t c : {node.first, node.first + 1}) {
      Box3f both = merge(node.box, bvh.nodes[c].box);
      EXPECT_TRUE(both.lo.x == node.box.lo.x && both.lo.y == node.box.lo.y &&
                  both.lo.z == node.box.lo.z && both.hi.x == node.box.hi.x &&
                  both.hi.y == node.box.hi.y && both.hi.z == node.box.hi.z);
    }
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(m.triangleCount()));
  int met = 0;
  for (int i = 0; i < 2000; ++i) {
    Vec3f c{u(rng), u(rng) * 0.8f, u(rng) * 0.8f};
    Vec3f h = Vec3f{1.0f, 1.0f, 1.0f} * (0.002f + 0.1f * std::abs(u(rng)));
    Box3f query{c - h, c + h};
    bool brute = false;
    for (size_t t = 0; t < m.triangleCount() && !brute; ++t)
      brute = boxesMeet(query, triangleBounds(m, t));
    EXPECT_EQ(anyTriangleBoxMeets(query, s), brute);
    met += brute;
  }
  EXPECT_GT(met, 200);
  EXPECT_LT(met, 1800);
}

TEST(MeshWorld, EmptyFlagsAndBoxBoundsAreConservative) {
  std::string path = writeTestMesh("conservative");
  for (float lattice : {0.0f, 1.5f}) {
    auto scene = MeshScene::load(path, lattice, Backend::Cpu);
    MeshWorld w = scene->hostWorld();
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int empties = 0, boxes = 0;
    for (int i = 0; i < 4000; ++i) {
      float v = MESH_VOXEL_SIZE0 * static_cast<float>(1 << (i % 7));
      Vec3d p{u(rng) * 1.2, u(rng) * 0.7, u(rng) * 1.2};
      if (w.voxel(p, v).empty) {
        ++empties;
        // Finer voxels within v of it are clear.
        for (int k = 0; k < 8; ++k) {
          Vec3d q{p.x + u(rng) * v, p.y + u(rng) * v, p.z + u(rng) * v};
          EXPECT_EQ(w.voxel(q, v / 2).rgba >> 24, 0u);
          EXPECT_EQ(w.voxel(q, v / 4).rgba >> 24, 0u);
        }
      }
      // A brick-sized box: when clear, every centre in it is flagged empty.
      double side = 8.0 * v;
      if (w.emptyBox(p, {p.x + side, p.y + side, p.z + side}, v)) {
        ++boxes;
        for (int k = 0; k < 6; ++k) {
          Vec3d c{p.x + side * (0.5 + 0.5 * u(rng)), p.y + side * (0.5 + 0.5 * u(rng)),
                  p.z + side * (0.5 + 0.5 * u(rng))};
          EXPECT_TRUE(w.voxel(c, v).empty);
        }
      }
    }
    EXPECT_GT(empties, 500);
    EXPECT_GT(boxes, 300);
  }
}

// A mesh sequence's options: the world, its movement, the size.
SequenceOptions meshOptions(const std::string& mesh, float lattice, Movement movement, int w,
                            int h) {
  SequenceOptions o;
  o.mesh = mesh;
  o.lattice = lattice;
  o.width = w;
  o.height = h;
  o.movement = movement;
  return o;
}

test::Renders meshRun(const std::string& mesh, float lattice, SchedulerKind kind, int frames,
                      Movement movement, Backend backend = Backend::Cpu, int w = 96, int h = 64) {
  SequenceOptions o = meshOptions(mesh, lattice, movement, w, h);
  o.frames = frames;
  o.scheduler = resolvedOptions({backend, kind, 0});
  return test::renderRun(o);
}

TEST(MeshCpu, SchedulersRenderTheSameFramesCloseToTheRayCast) {
  std::string path = writeTestMesh("frames");
  struct Case {
    float lattice;
    Movement movement;
    double minPsnr;  // against the ray cast (measured: 31.8 / 27.9 dB at 96x64)
  };
  for (Case c : {Case{0.0f, Movement::Orbit, 28.0}, Case{1.5f, Movement::Walkthrough, 25.0}}) {
    const int FRAMES = 2;
    test::Renders sp = meshRun(path, c.lattice, SchedulerKind::Sp, FRAMES, c.movement);
    for (SchedulerKind k : {SchedulerKind::Dp, SchedulerKind::Pt}) {
      test::Renders r = meshRun(path, c.lattice, k, FRAMES, c.movement);
      for (int f = 0; f < FRAMES; ++f) {
        EXPECT_EQ(r.images[f].pixels, sp.images[f].pixels) << schedulerName(k) << " frame " << f;
        EXPECT_EQ(r.stats[f].unfinishedPixels, 0);
      }
    }
    test::Renders direct = meshRun(path, c.lattice, SchedulerKind::Direct, FRAMES, c.movement);
    auto scene = MeshScene::load(path, c.lattice, Backend::Cpu);
    SequenceOptions o = meshOptions(path, c.lattice, c.movement, 96, 64);
    for (int f = 0; f < FRAMES; ++f) {
      EXPECT_EQ(sp.stats[f].unfinishedPixels, 0);
      EXPECT_GT(psnr(sp.images[f], direct.images[f]), 40.0) << "frame " << f;
      Image reference;
      scene->renderReference(frameOf(o, f), reference);
      double db = psnr(sp.images[f], reference);
      std::printf("lattice %.1f frame %d: PSNR against the ray cast %.2f dB\n", c.lattice, f, db);
      EXPECT_GT(db, c.minPsnr) << "frame " << f;
    }
    EXPECT_GT(sp.stats[0].cache.produced, 50u);  // the mesh is in view
  }
}

// Every GPU scheduler renders sp's frames bit for bit; the GPU's frames are close to the CPU's
// and to the ray cast.
TEST(MeshGpu, SchedulersRenderTheSameFramesCloseToTheCpuAndTheRayCast) {
  GVDP_REQUIRE_GPU();
  std::string path = writeTestMesh("gpu");
  const int FRAMES = 6, W = 320, H = 200;
  for (float lattice : {0.0f, 1.5f}) {
    Movement movement = lattice == 0.0f ? Movement::Orbit : Movement::Walkthrough;
    test::Renders sp =
        meshRun(path, lattice, SchedulerKind::Sp, FRAMES, movement, Backend::Cuda, W, H);
    for (SchedulerKind k : {SchedulerKind::Dp, SchedulerKind::Pt, SchedulerKind::Graph}) {
      test::Renders r = meshRun(path, lattice, k, FRAMES, movement, Backend::Cuda, W, H);
      for (int f = 0; f < FRAMES; ++f) {
        EXPECT_EQ(r.images[f].pixels, sp.images[f].pixels) << schedulerName(k) << " frame " << f;
        EXPECT_EQ(r.stats[f].unfinishedPixels, 0);
      }
    }
    test::Renders cpu = meshRun(path, lattice, SchedulerKind::Sp, 2, movement, Backend::Cpu, W, H);
    auto scene = MeshScene::load(path, lattice, Backend::Cpu);
    SequenceOptions o = meshOptions(path, lattice, movement, W, H);
    for (int f = 0; f < 2; ++f) {
      Image reference;
      scene->renderReference(frameOf(o, f), reference);
      double gpuCpu = psnr(sp.images[f], cpu.images[f]), gpuRay = psnr(sp.images[f], reference);
      std::printf("lattice %.1f frame %d: GPU against CPU %.2f dB, against the ray cast %.2f dB\n",
                  lattice, f, gpuCpu, gpuRay);
      EXPECT_GT(gpuCpu, 40.0);
      EXPECT_GT(gpuRay, 25.0);
    }
  }
}

TEST(MeshCli, BadMeshInputIsOneLineWithStatus2) {
  std::string path = writeTestMesh("cli");
  struct Bad {
    std::string args, says;
  } cases[] = {
      {"--mesh /nonexistent/x.off", "/nonexistent/x.off"},
      {"--mesh " + path + " --lattice 0.5", "--lattice 0.5"},
      {"--mesh " + path + " --lattice nan", "--lattice"},
      {"--lattice 2", "needs --mesh"},
      {"--reference", "needs --mesh"},
      {"--mesh " + path + " --movement circle", "circle"},
  };
  for (const Bad& b : cases) {
    test::CommandResult r = test::runGvdp("render --backend cpu --frames 1 --out " +
                                          test::tempDir("cli_out") + " " + b.args);
    EXPECT_EQ(r.status, 2) << b.args << ": " << r.output;
    EXPECT_NE(r.output.find(b.says), std::string::npos) << b.args << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << b.args << ": " << r.output;
  }
  std::string out = test::tempDir("cli_good");
  test::CommandResult good = test::runGvdp(
      "render --backend cpu --frames 1 --width 64 --height 40 "
      "--movement orbit --reference --mesh " +
      path + " --out " + out);
  EXPECT_EQ(good.status, 0) << good.output;
  EXPECT_NE(good.output.find("PSNR against the ray cast"), std::string::npos) << good.output;
}

}  // namespace
}  // namespace gvdp::detail
