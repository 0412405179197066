// gvdp mesh subdivide / sphere, gvdp kdtree (mesh_commands.h). Figures printed by kdtree: the
// build time is the median of --repeat builds (the GPU's after one warm-up build, wall clock from
// the mesh on the host to the tree on the host); rays go from a sphere around the mesh's box
// (radius: the box's diagonal) to uniform points inside it, the same rays for one thread and for
// the pool.
#include "mesh_commands.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <vector>

#include "gvdp/base/error.h"
#include "gvdp/base/gpu.h"
#include "gvdp/base/parallel.h"
#include "gvdp/mesh/kdtree_build.h"
#include "gvdp/mesh/kdtree_raycast.h"
#include "gvdp/mesh/kdtree_stats.h"
#include "gvdp/mesh/mesh_io.h"
#include "gvdp/mesh/mesh_subdivide.h"

namespace gvdp::detail {
namespace {

constexpr int MAX_TIMES = 8;
constexpr int64_t MAX_REPEAT = 1000;
constexpr int64_t MAX_RAYS = 100000000;

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

std::vector<Ray> randomRays(Box3f box, int64_t count) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Vec3f centre = (box.lo + box.hi) * 0.5f, size = box.hi - box.lo;
  float radius = std::max(length(size), 1e-6f);
  std::vector<Ray> rays(static_cast<size_t>(count));
  for (Ray& r : rays) {
    Vec3f dir{0.0f, 0.0f, 0.0f};
    while (dot(dir, dir) < 1e-4f || dot(dir, dir) > 1.0f)
      dir = {2.0f * u(rng) - 1.0f, 2.0f * u(rng) - 1.0f, 2.0f * u(rng) - 1.0f};
    r.o = centre + normalize(dir) * radius;
    Vec3f target = box.lo + Vec3f{u(rng), u(rng), u(rng)} * size;
    r.d = normalize(target - r.o);
  }
  return rays;
}

std::string poolName() {
  int n = ThreadPool::global().size();
  return "pool of " + std::to_string(n) + (n == 1 ? " thread" : " threads");
}

struct Timed {
  double ms = 0.0;
  KdTree tree;
};

template <class Build>
Timed timeBuilds(const Mesh& mesh, int64_t repeat, Build build, bool warmUp = false) {
  std::vector<double> ms;
  Timed t;
  if (warmUp) t.tree = build(mesh);
  for (int64_t i = 0; i < repeat; ++i) {
    auto start = std::chrono::steady_clock::now();
    t.tree = build(mesh);
    ms.push_back(msSince(start));
  }
  std::sort(ms.begin(), ms.end());
  t.ms = ms[ms.size() / 2];
  return t;
}

void printTree(const std::string& label, const Timed& t, int64_t repeat) {
  KdTreeStats s = kdTreeStats(t.tree);
  std::printf("%s: %.1f ms (median of %lld)\n", label.c_str(), t.ms,
              static_cast<long long>(repeat));
  std::printf(
      "  SAH cost %.3f, %zu nodes, %zu leaves (%zu empty), max depth %d, %.2f triangles per "
      "leaf\n",
      s.sahCost, s.nodes, s.leaves, s.emptyLeaves, s.maxDepth, s.meanLeafTriangles);
}

int runKdTree(const std::string& path, const std::string& builders, int64_t repeat, int64_t rays) {
  GVDP_INPUT_CHECK(repeat >= 1 && repeat <= MAX_REPEAT, "--repeat ", repeat, " (expected 1..",
                   MAX_REPEAT, ")");
  GVDP_INPUT_CHECK(rays >= 1 && rays <= MAX_RAYS, "--rays ", rays, " (expected 1..", MAX_RAYS, ")");
  bool sequentialOnly = builders == "sequential", levelOnly = builders == "level",
       gpuOnly = builders == "gpu", all = builders == "all";
  GVDP_INPUT_CHECK(sequentialOnly || levelOnly || gpuOnly || all, "--builders '", builders,
                   "' (expected sequential, level, gpu or all)");
  bool haveGpu = cudaBuilt() && cudaDeviceAvailable();
  GVDP_INPUT_CHECK(!gpuOnly || haveGpu, "--builders gpu: no GPU (", cudaDeviceSummary(), ")");
  Mesh mesh = readMesh(path);
  placeMesh(mesh);
  std::printf("mesh: %s, %zu triangles, %zu vertices (placed: longest side %.1f)\n", path.c_str(),
              mesh.triangleCount(), mesh.vertices.size(), static_cast<double>(MESH_PLACED_SIZE));
  Timed seq, level, gpu;
  if (!levelOnly) {
    seq = timeBuilds(mesh, repeat, buildKdTreeSequential);
    printTree("sequential build", seq, repeat);
  }
  if (levelOnly || all) {
    level = timeBuilds(mesh, repeat, buildKdTreeParallel);
    printTree("level-by-level build (" + poolName() + ")", level, repeat);
    if (!levelOnly) {
      std::string why;
      GVDP_CHECK(sameTree(seq.tree, level.tree, &why), "the builders' trees differ ", why);
      std::printf("  the same tree as the sequential builder's (sameTree)\n");
    }
  }
  if (gpuOnly || (all && haveGpu)) {
    KdBuildPhases phases;
    gpu = timeBuilds(
        mesh, repeat, [&](const Mesh& m) { return buildKdTreeCuda(m, &phases); }, true);
    printTree("gpu build (after a warm-up; upload and download included)", gpu, repeat);
    std::printf("  the last build: upload and root %.1f ms, %d levels %.1f ms, download %.1f ms\n",
                phases.rootMs, phases.levels, phases.levelsMs, phases.downloadMs);
    std::printf("  %.1fx the sequential build's speed\n", seq.ms / std::max(gpu.ms, 1e-6));
    std::string why;
    bool same = sameTree(seq.tree, gpu.tree, &why);
    std::printf("gpu tree equals the sequential tree: %s\n", same ? "yes" : "no");
    GVDP_CHECK(same, "the GPU builder's tree differs from the sequential one's ", why);
  }
  const KdTree& tree = levelOnly ? level.tree : seq.tree;

  std::vector<Ray> rs = randomRays(tree.bounds, rays);
  MeshView mv{mesh.vertices.data(), mesh.indices.data(),
              static_cast<uint32_t>(mesh.triangleCount())};
  KdTreeView tv = tree.view();
  std::vector<uint32_t> hitsOne(rs.size()), hitsPool(rs.size());
  auto start = std::chrono::steady_clock::now();
  for (size_t i = 0; i < rs.size(); ++i) hitsOne[i] = closestHit(rs[i], tv, mv).triangle;
  double oneMs = msSince(start);
  start = std::chrono::steady_clock::now();
  parallelFor(
      static_cast<int64_t>(rs.size()),
      [&](int64_t i) { hitsPool[static_cast<size_t>(i)] = closestHit(rs[i], tv, mv).triangle; },
      256);
  double poolMs = msSince(start);
  GVDP_CHECK(hitsOne == hitsPool, "the pool's ray casts differ from one thread's");
  size_t hits = static_cast<size_t>(
      std::count_if(hitsOne.begin(), hitsOne.end(), [](uint32_t t) { return t != KD_NO_HIT; }));
  std::printf("rays: %zu through the box, %zu hit; 1 thread %.3f Mrays/s, %s %.3f Mrays/s\n",
              rs.size(), hits, static_cast<double>(rs.size()) / oneMs / 1e3, poolName().c_str(),
              static_cast<double>(rs.size()) / poolMs / 1e3);
  return 0;
}

void checkPlyOut(const std::string& out) {
  std::string ext = out.size() >= 4 ? out.substr(out.size() - 4) : "";
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  GVDP_INPUT_CHECK(ext == ".ply", out, ": the output must be a .ply file");
}

int runSubdivide(const std::string& in, const std::string& out, int times) {
  GVDP_INPUT_CHECK(times >= 1 && times <= MAX_TIMES, "--times ", times, " (expected 1..", MAX_TIMES,
                   ")");
  checkPlyOut(out);
  Mesh mesh = readMesh(in);
  GVDP_INPUT_CHECK(mesh.triangleCount() << (2 * times) < (size_t{1} << 30), in, ": ",
                   mesh.triangleCount(), " triangles subdivided ", times,
                   " times would be over 2^30 triangles");
  auto start = std::chrono::steady_clock::now();
  Mesh fine = subdivide(mesh, times);
  double ms = msSince(start);
  writePly(fine, out);
  std::printf("%s: %zu triangles -> %s: %zu triangles, %zu vertices (%.0f ms)\n", in.c_str(),
              mesh.triangleCount(), out.c_str(), fine.triangleCount(), fine.vertices.size(), ms);
  return 0;
}

// An icosahedron subdivided `times` times, its vertices pushed to the unit sphere: 20 * 4^times
// triangles (times 8: 1,310,720), a large mesh made anywhere.
int runSphere(const std::string& out, int times) {
  GVDP_INPUT_CHECK(times >= 0 && times <= MAX_TIMES, "--times ", times, " (expected 0..", MAX_TIMES,
                   ")");
  checkPlyOut(out);
  Mesh m = icosphere(times);
  writePly(m, out);
  std::printf("icosphere: %zu triangles, %zu vertices -> %s\n", m.triangleCount(),
              m.vertices.size(), out.c_str());
  return 0;
}

}  // namespace

MeshCommands::MeshCommands(CLI::App& app) {
  mesh_ = app.add_subcommand("mesh", "mesh tools: subdivide, sphere");
  mesh_->allow_extras();  // an unknown mesh command is refused by runParsed, naming it
  subdivide_ = mesh_->add_subcommand(
      "subdivide", "1-to-4 midpoint subdivision, N times (triangles x 4^N), to binary PLY");
  subdivide_->add_option("--times", times_, "subdivisions, 1.." + std::to_string(MAX_TIMES));
  subdivide_->add_option("in", in_, "the mesh (.off, .ply, .obj)")->required();
  subdivide_->add_option("out", out_, "the result (.ply, binary)")->required();
  sphere_ = mesh_->add_subcommand(
      "sphere", "an icosphere: an icosahedron subdivided N times (20 x 4^N triangles), to PLY");
  sphere_->add_option("--times", sphereTimes_,
                      "subdivisions, 0.." + std::to_string(MAX_TIMES) + " (default 5)");
  sphere_->add_option("out", sphereOut_, "the result (.ply, binary)")->required();
  kdtree_ = app.add_subcommand(
      "kdtree", "build a mesh's full-SAH kd-tree (Wald-Havran), time it and its ray casts");
  kdtree_->add_option("--mesh", kdMesh_, "the mesh (.off, .ply, .obj)")->required();
  kdtree_->add_option("--repeat", repeat_, "builds timed (the median is printed; default 3)");
  kdtree_->add_option("--rays", rays_, "random rays cast (default 200000)");
  kdtree_->add_option("--builders", builders_,
                      "sequential, level (seed 004's level by level, on the pool), gpu (the "
                      "same on the GPU, against the sequential) or all (default: every one "
                      "there is, their trees compared)");
}

std::optional<int> MeshCommands::runParsed() const {
  if (mesh_->parsed() && !subdivide_->parsed() && !sphere_->parsed()) {
    std::vector<std::string> rest = mesh_->remaining();
    GVDP_INPUT_CHECK(false,
                     rest.empty() ? std::string("gvdp mesh needs a command")
                                  : "unknown mesh command '" + rest[0] + "'",
                     " (commands: subdivide, sphere)");
  }
  if (subdivide_->parsed()) return runSubdivide(in_, out_, times_);
  if (sphere_->parsed()) return runSphere(sphereOut_, sphereTimes_);
  if (kdtree_->parsed()) return runKdTree(kdMesh_, builders_, repeat_, rays_);
  return std::nullopt;
}

}  // namespace gvdp::detail
