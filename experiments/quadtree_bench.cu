// Experiment (seed paper, "GPU quadtree subdivision for out-of-core rendering"): the seed's
// subtree kernels (L levels per pass) against its baseline (a pass per level, the host reading
// the counts back each time) and against CUDA Dynamic Parallelism (a device launch per
// subdivided node), over importance maps shaped like a terrain frame.
//
// For each map (synthetic: 2^K blocks wide, 9:16 high, a horizon, ground needing more the lower
// it is, noise; or a raw little-endian uint32 file) and a few capacities (the tile count from
// ~10 to ~100 000), times each GPU method's subdivision with CUDA events (run(): passes, host
// read-backs and all; not the tiles' download), median of --runs after --warmup runs, checks its
// tiles equal the CPU reference's (exit 1 otherwise) and prints a row: K, capacity, tiles, passes,
// method, L, median ms, speed-up over MultiPass.
//
// Usage: gvdp_quadtree_bench [--k 10,11,12] [--importance FILE --width W --height H]
//          [--block-pixels 16] [--max-tile-pixels P] [--capacities C1,C2,..] [--runs 20]
//          [--warmup 3] [--json FILE]
#include <cuda_runtime.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "experiment_main.h"
#include "gvdp/base/cuda_util.h"
#include "gvdp/tiles/quadtree.h"

namespace gvdp::detail {
namespace {

struct Options {
  std::vector<int> levels{10, 11, 12};
  std::string importance;
  int width = 0, height = 0;
  int blockPixels = 16;
  int64_t maxTilePixels = std::numeric_limits<int64_t>::max();
  std::vector<uint64_t> capacities;  // empty: chosen per map
  int runs = 20, warmup = 3;
  std::string json;
};

struct Map {
  std::string name;
  int width, height;
  std::vector<uint32_t> values;
};

struct Row {
  std::string map;
  int levels;
  uint64_t capacity, tiles;
  int passes;
  uint64_t deviceLaunches;  // Dynamic
  std::string method;
  int levelsPerPass;
  double ms, speedup;
};

template <class T>
std::vector<T> parseList(const char* s) {
  std::vector<T> out;
  for (const char* p = s; *p;) {
    char* end = nullptr;
    out.push_back(static_cast<T>(std::strtoull(p, &end, 10)));
    GVDP_INPUT_CHECK(end != p, "bad number list '", s, "'");
    p = *end == ',' ? end + 1 : end;
  }
  return out;
}

Options parseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    GVDP_INPUT_CHECK(i + 1 < argc, "option ", a, " needs a value");
    const char* v = argv[++i];
    if (a == "--k")
      o.levels = parseList<int>(v);
    else if (a == "--importance")
      o.importance = v;
    else if (a == "--width")
      o.width = std::atoi(v);
    else if (a == "--height")
      o.height = std::atoi(v);
    else if (a == "--block-pixels")
      o.blockPixels = std::atoi(v);
    else if (a == "--max-tile-pixels")
      o.maxTilePixels = std::atoll(v);
    else if (a == "--capacities")
      o.capacities = parseList<uint64_t>(v);
    else if (a == "--runs")
      o.runs = std::max(1, std::atoi(v));
    else if (a == "--warmup")
      o.warmup = std::max(0, std::atoi(v));
    else if (a == "--json")
      o.json = v;
    else
      throw InputError("unknown option " + a);
  }
  return o;
}

// A frame over terrain: a wavy horizon, sky needing almost nothing, ground needing more the
// nearer (lower) it is, rough noise and a few dense patches. Deterministic.
Map syntheticMap(int levels) {
  int w = 1 << levels, h = std::max(1, (w * 9) / 16);
  std::mt19937 rng(1234u + static_cast<uint32_t>(levels));
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Map m{"terrain K=" + std::to_string(levels), w, h, std::vector<uint32_t>(size_t(w) * h)};
  for (int x = 0; x < w; ++x) {
    float fx = static_cast<float>(x) / static_cast<float>(w);
    float horizon = 0.3f + 0.06f * std::sin(6.2832f * 3.0f * fx) + 0.03f * std::sin(41.0f * fx);
    for (int y = 0; y < h; ++y) {
      float fy = static_cast<float>(y) / static_cast<float>(h);
      float v = fy < horizon ? (u(rng) < 0.1f ? 1.0f : 0.0f)
                             : 1.0f + 120.0f * std::pow((fy - horizon) / (1.0f - horizon), 2.0f) *
                                          (0.5f + u(rng));
      if (u(rng) < 0.01f) v *= 8.0f;
      m.values[size_t(y) * w + x] = static_cast<uint32_t>(v);
    }
  }
  return m;
}

Map fileMap(const Options& o) {
  GVDP_INPUT_CHECK(o.width > 0 && o.height > 0, "--importance needs --width and --height");
  std::ifstream in(o.importance, std::ios::binary);
  GVDP_INPUT_CHECK(in, "cannot read ", o.importance);
  Map m{o.importance, o.width, o.height, std::vector<uint32_t>(size_t(o.width) * o.height)};
  in.read(reinterpret_cast<char*>(m.values.data()), std::streamsize(m.values.size() * 4));
  GVDP_INPUT_CHECK(in.gcount() == std::streamsize(m.values.size() * 4), o.importance,
                   " holds fewer than ", o.width, "x", o.height, " uint32 values");
  return m;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Median ms of run() over `runs` runs after `warmup`; -1 when the method is not built.
double timeMethod(GpuQuadtree& gpu, const SubdivisionParams& p, GpuSubdivision m, const Options& o,
                  cudaStream_t stream) {
  GpuTimer timer;
  for (int i = 0; i < o.warmup; ++i) gpu.run(p, m.method, m.levelsPerPass, stream);
  std::vector<double> ms;
  for (int i = 0; i < o.runs; ++i) {
    timer.start(stream);
    gpu.run(p, m.method, m.levelsPerPass, stream);
    timer.stop(stream);
    ms.push_back(timer.ms());
  }
  return median(ms);
}

// Capacities splitting the map's total need into ~10 .. ~100 000 tiles.
std::vector<uint64_t> capacitiesFor(const SumMipmap& m, const Options& o) {
  if (!o.capacities.empty()) return o.capacities;
  std::vector<uint64_t> c;
  for (uint64_t tiles : {10, 100, 1000, 10000, 100000})
    c.push_back(std::max<uint64_t>(1, m.values[0] / tiles));
  return c;
}

bool benchMap(const Map& map, const Options& o, cudaStream_t stream, std::vector<Row>& rows) {
  SumMipmap cpu = buildSumMipmap(map.values.data(), map.width, map.height);
  GpuQuadtree gpu;
  gpu.upload(map.values.data(), map.width, map.height, stream);
  std::vector<double> buildMs;
  GpuTimer timer;
  for (int i = 0; i < o.warmup + o.runs; ++i) {
    timer.start(stream);
    gpu.buildMipmap(stream);
    timer.stop(stream);
    if (i >= o.warmup) buildMs.push_back(timer.ms());
  }
  bool ok = gpu.downloadMipmap(stream).values == cpu.values;
  std::printf("\n%s: %dx%d blocks, K=%d, total %llu; GPU sum-mipmap %.3f ms%s\n", map.name.c_str(),
              map.width, map.height, cpu.levels, static_cast<unsigned long long>(cpu.values[0]),
              median(buildMs), ok ? "" : "  MISMATCH against the CPU's");
  std::printf("%3s %14s %8s %6s %10s %2s %10s %8s\n", "K", "capacity", "tiles", "passes", "method",
              "L", "median_ms", "speedup");
  for (uint64_t capacity : capacitiesFor(cpu, o)) {
    SubdivisionParams p{capacity, o.maxTilePixels, o.blockPixels, map.width * o.blockPixels,
                        map.height * o.blockPixels};
    std::vector<Tile> reference = subdivide(cpu, p);
    sortCanonical(reference, cpu.levels);
    double multiPassMs = 0;
    for (GpuSubdivision m : gpuSubdivisions()) {
      SubdivisionStats stats;
      std::vector<Tile> tiles;
      try {
        gpu.run(p, m.method, m.levelsPerPass, stream, &stats);
        tiles = gpu.tiles(stream);
      } catch (const InputError& e) {  // Dynamic without CDP
        std::printf("%3d %14llu %8s %6s %10s %2s %10s %8s  (%s)\n", cpu.levels,
                    static_cast<unsigned long long>(capacity), "-", "-", methodName(m.method), "-",
                    "-", "-", e.what());
        continue;
      }
      sortCanonical(tiles, cpu.levels);
      bool same = tiles == reference;
      ok = ok && same;
      double ms = timeMethod(gpu, p, m, o, stream);
      if (m.method == SubdivisionMethod::MultiPass) multiPassMs = ms;
      Row r{.map = map.name,
            .levels = cpu.levels,
            .capacity = capacity,
            .tiles = reference.size(),
            .passes = stats.passes,
            .deviceLaunches = stats.deviceLaunches,
            .method = methodName(m.method),
            .levelsPerPass = m.levelsPerPass,
            .ms = ms,
            .speedup = multiPassMs / ms};
      std::printf("%3d %14llu %8llu %6d %10s %2d %10.4f %7.2fx", r.levels,
                  static_cast<unsigned long long>(r.capacity),
                  static_cast<unsigned long long>(r.tiles), r.passes, r.method.c_str(),
                  r.levelsPerPass, r.ms, r.speedup);
      if (r.deviceLaunches)
        std::printf("  (%llu device launches)", static_cast<unsigned long long>(r.deviceLaunches));
      std::printf("%s\n", same ? "" : "  MISMATCH against the CPU's");
      rows.push_back(r);
    }
  }
  return ok;
}

void writeJson(const std::string& path, const std::vector<Row>& rows) {
  FILE* f = std::fopen(path.c_str(), "w");
  GVDP_INPUT_CHECK(f, "cannot write ", path);
  std::fprintf(f, "[\n");
  for (size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    std::fprintf(f,
                 "  {\"map\": \"%s\", \"K\": %d, \"capacity\": %llu, \"tiles\": %llu, "
                 "\"passes\": %d, \"device_launches\": %llu, \"method\": \"%s\", \"L\": %d, "
                 "\"median_ms\": %.6f, \"speedup\": %.4f}%s\n",
                 r.map.c_str(), r.levels, static_cast<unsigned long long>(r.capacity),
                 static_cast<unsigned long long>(r.tiles), r.passes,
                 static_cast<unsigned long long>(r.deviceLaunches), r.method.c_str(),
                 r.levelsPerPass, r.ms, r.speedup, i + 1 < rows.size() ? "," : "");
  }
  std::fprintf(f, "]\n");
  std::fclose(f);
}

int run(int argc, char** argv) {
  Options o = parseOptions(argc, argv);
  GVDP_INPUT_CHECK(cudaDeviceAvailable(), "needs a CUDA device: ", cudaDeviceSummary());
  std::vector<Map> maps;
  if (!o.importance.empty())
    maps.push_back(fileMap(o));
  else
    for (int k : o.levels) maps.push_back(syntheticMap(k));
  cudaStream_t stream = nullptr;
  GVDP_CUDA_CHECK(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));
  std::vector<Row> rows;
  bool ok = true;
  for (const Map& m : maps) ok = benchMap(m, o, stream, rows) && ok;
  GVDP_CUDA_CHECK(cudaStreamDestroy(stream));
  if (!o.json.empty()) writeJson(o.json, rows);
  if (!ok) std::fprintf(stderr, "gvdp_quadtree_bench: a GPU result differs from the CPU's\n");
  return ok ? 0 : 1;
}

}  // namespace
}  // namespace gvdp::detail

int main(int argc, char** argv) {
  return gvdp::detail::experimentMain("gvdp_quadtree_bench", gvdp::detail::run, argc, argv);
}
