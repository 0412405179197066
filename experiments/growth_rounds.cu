// Experiment (issue 14, "shorter productions"): how long a round of an EMPTY brick's box growth
// (cache/produce.h: growEmptyBoxes) takes one warp, with its code cold and hot. pt's frames spend
// 60-75% of a production's latency in this growth (BENCHMARKS.md, sessions 37-38), 3-5 rounds a
// growth on real frames, and each round is one bound test per lane: the question is whether a
// round's 11-13 us are the test's own instructions or fetching them.
//
// For each world, empty bricks drawn near the ground and above it (levels 0-5, as the CPU test
// Cache.GroupsGrowEmptyBoxesAheadInFewerRounds draws them; the host's bound keeps those it
// clears), grown by one warp of one block, ancestors included as if every one were markable:
// The kernel has pt's worker's bounds (80 registers).
//   cold  the first growth of a launch that follows another world's launch (its code is in L2,
//         not in the SM's instruction caches);
//   hot   the growths after it in the same launch (the same code, just run).
// each alone on its SM, and with a crowd of --crowd more warps in its block (and of --blocks - 1
// more blocks of as many, so that its SM holds three blocks as pt's worker's does): growing the
// same world's bricks through the same code (the SM's issue slots shared), or the other four
// worlds' (the slots shared and the instruction caches holding five worlds' code), until warp 0 is
// done. Each round is timed with clock64() at the group's any() (the end of its tests); cycles
// become microseconds by the kernel's own clock64/globaltimer ratio. Prints per world, crowd and
// kind: growths, rounds a growth, and the median and mean us a round and a growth.
//
// Usage: gvdp_growth_rounds [--bricks N] [--launches L] [--crowd W] [--blocks B]
//          (default 64, 24, 7, 1)
#include <cuda_runtime.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "experiment_main.h"
#include "gvdp/base/clock.h"
#include "gvdp/base/cooperation.h"
#include "gvdp/base/cuda_util.h"
#include "gvdp/cache/clipmap.h"
#include "gvdp/cache/produce.h"
#include "gvdp/mesh/text_tokens.h"
#include "gvdp/render/frame.h"
#include "gvdp/world/registry.h"

namespace gvdp::detail {
namespace {

constexpr int MAX_ROUNDS = 256;  // per growth, ancestors' included

// A warp's scope (what growEmptyBoxes uses of one) that stamps the SM's clock at every any():
// a round ends there. Without stamps (a crowd's warp) it records nothing, through the same code.
struct TimedWarp {
  int lane;
  long long* stamps;  // MAX_ROUNDS, written by lane 0; null: none
  int* rounds;
  __device__ int rank() const { return lane; }
  __device__ int size() const { return 32; }
  __device__ uint32_t any(uint32_t bits) const {
    uint32_t r = __reduce_or_sync(0xffffffffu, bits);
    if (lane == 0 && stamps && *rounds < MAX_ROUNDS) stamps[(*rounds)++] = clock64();
    return r;
  }
};

struct GrowthRecord {
  long long start, end;  // clock64 around the growth
  int rounds;
  long long stamps[MAX_ROUNDS];
};

struct ClockRecord {
  long long cycles0, cycles1;
  unsigned long long ns0, ns1;
};

// What the block's other warps do while warp 0 grows its bricks, timed.
enum class Crowd : int {
  None,   // nothing (the block is one warp)
  Same,   // the same world's growths, through the same code as warp 0's: the SM's issue slots
          // shared
  Others  // the other four worlds' growths (each world's code inlined apart): the slots shared
          // and four times the code in the SM's instruction caches
};

struct Worlds {
  BuiltinScene scene[SCENE_COUNT];
  const BrickKey* keys[SCENE_COUNT];
  int count[SCENE_COUNT];
};

// pt's worker's bounds (sched/pt/pt_worker.cuh: 256 threads, 3 blocks an SM, so 80 registers).
template <class P>
__global__ void __launch_bounds__(256, 3)
    growKernel(P world, Clipmap clipmap, const BrickKey* keys, int n, Crowd crowd,
               const __grid_constant__ Worlds worlds, int self, GrowthRecord* out,
               ClockRecord* clock, volatile int* finished, uint32_t* sink) {
  // Block 0's warp 0 is timed; every other warp of the grid is the crowd.
  const int lane = static_cast<int>(threadIdx.x & 31u);
  const int warp = static_cast<int>(threadIdx.x >> 5 | blockIdx.x * (blockDim.x >> 5));
  if (warp == 0 && lane == 0) {
    clock->cycles0 = clock64();
    clock->ns0 = clockNanoseconds();
  }
  uint32_t entries = 0;
  auto publish = [&](const BrickKey& k, uint32_t entry) {
    entries ^= entry;
    return k.level + 1 < clipmap.levels;
  };
  if (warp > 0 && crowd == Crowd::Others) {
    for (int i = 0; !*finished; ++i) {
      int s = (self + 1 + (warp + i) % (SCENE_COUNT - 1)) % SCENE_COUNT;
      const BrickKey& key = worlds.keys[s][(i * 31 + warp) % worlds.count[s]];
      worlds.scene[s].visit(
          [&](const auto& w) { growEmptyBoxes(WarpScope{lane}, w, key, clipmap, publish); });
    }
  } else {
    for (int i = 0; warp == 0 ? i < n : !*finished; ++i) {
      GrowthRecord* r = warp == 0 ? &out[i] : nullptr;
      if (r && lane == 0) {
        r->rounds = 0;
        r->start = clock64();
      }
      __syncwarp();
      TimedWarp group{lane, r ? r->stamps : nullptr, r ? &r->rounds : nullptr};
      growEmptyBoxes(group, world, keys[warp == 0 ? i : (i * 31 + warp) % n], clipmap, publish);
      __syncwarp();
      if (r && lane == 0) r->end = clock64();
    }
    if (warp == 0 && lane == 0) *finished = 1;
  }
  if (warp == 0 && lane == 0) {
    clock->cycles1 = clock64();
    clock->ns1 = clockNanoseconds();
  }
  if (entries == 0x12345678u) *sink = entries;  // the growths' results are used
}

struct Stats {
  std::vector<double> roundUs, growthUs;
  long rounds = 0, growths = 0;
  void add(const GrowthRecord& r, double usPerCycle) {
    ++growths;
    rounds += r.rounds;
    growthUs.push_back(static_cast<double>(r.end - r.start) * usPerCycle);
    long long last = r.start;
    for (int k = 0; k < r.rounds && k < MAX_ROUNDS; ++k) {
      roundUs.push_back(static_cast<double>(r.stamps[k] - last) * usPerCycle);
      last = r.stamps[k];
    }
  }
};

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}
double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

// Empty bricks of a world as the CPU test draws them, half near the ground.
std::vector<BrickKey> emptyBricks(const BuiltinScene& world, int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<BrickKey> keys;
  for (int i = 0; keys.size() < static_cast<size_t>(count) && i < 100000; ++i) {
    int level = static_cast<int>(rng() % 6u);
    auto coord = [&](int lo, int hi) { return lo + static_cast<int>(rng() % (hi - lo)); };
    int y = i % 2 ? coord(-4, 400) >> level : coord(-4, 12) >> level;
    BrickKey key{{coord(-40, 40), y, coord(-40, 40)}, level};
    if (brickBoundedEmpty(world, key)) keys.push_back(key);
  }
  return keys;
}

struct Run {
  const char* name;
  BuiltinScene world;
  std::vector<BrickKey> keys;
  BrickKey* deviceKeys = nullptr;
};

int run(int argc, char** argv) {
  int bricks = 64, launches = 24, crowdWarps = 7, blocks = 1;
  struct Option {
    const char* name;
    int* value;
    int64_t lo, hi;
  };
  const Option options[] = {{"--bricks", &bricks, 2, 4096},
                            {"--launches", &launches, 1, 1000},
                            {"--crowd", &crowdWarps, 1, 7},
                            {"--blocks", &blocks, 1, 100000}};
  for (int i = 1; i < argc; ++i) {
    auto o = std::find_if(std::begin(options), std::end(options),
                          [&](const Option& opt) { return !std::strcmp(argv[i], opt.name); });
    if (o == std::end(options)) throw InputError(concat("unknown option '", argv[i], "'"));
    if (++i == argc) throw InputError(concat(o->name, " needs a value"));
    int64_t v = 0;
    if (!parseInt(argv[i], v) || v < o->lo || v > o->hi)
      throw InputError(
          concat("bad ", o->name, " '", argv[i], "' (expected ", o->lo, "..", o->hi, ")"));
    *o->value = static_cast<int>(v);
  }
  const char* names[] = {"perlin", "fbm", "forest", "random-spheres", "aligned-spheres"};
  std::vector<Run> runs;
  for (const char* name : names) {
    Run r{name, findScene(name).world, {}, nullptr};
    r.keys = emptyBricks(r.world, bricks, 11);
    GVDP_CUDA_CHECK(cudaMalloc(&r.deviceKeys, r.keys.size() * sizeof(BrickKey)));
    GVDP_CUDA_CHECK(cudaMemcpy(r.deviceKeys, r.keys.data(), r.keys.size() * sizeof(BrickKey),
                               cudaMemcpyHostToDevice));
    runs.push_back(std::move(r));
  }
  // The clipmap of the CPU test's frame (its eye decides the faces a box grows through).
  const SceneInfo& perlin = findScene("perlin");
  const Clipmap clipmap =
      clipmapOf(makeFrame({{0.3, 3.0, 0.3}, 0.3f, 0.0f}, perlin.world.voxelSize0(), 64, 40, 5, 0));
  GrowthRecord* records = nullptr;
  ClockRecord* clock = nullptr;
  uint32_t* sink = nullptr;
  int* finished = nullptr;
  GVDP_CUDA_CHECK(cudaMalloc(&records, sizeof(GrowthRecord) * bricks));
  GVDP_CUDA_CHECK(cudaMalloc(&clock, sizeof(ClockRecord)));
  GVDP_CUDA_CHECK(cudaMalloc(&sink, sizeof(uint32_t)));
  GVDP_CUDA_CHECK(cudaMalloc(&finished, sizeof(int)));
  Worlds worlds{};
  for (int w = 0; w < SCENE_COUNT; ++w) {
    worlds.scene[w] = runs[w].world;
    worlds.keys[w] = runs[w].deviceKeys;
    worlds.count[w] = static_cast<int>(runs[w].keys.size());
  }
  std::vector<GrowthRecord> host(bricks);
  for (const Run& r : runs) {
    cudaFuncAttributes a{};
    r.world.visit([&](const auto& w) {
      using W = std::decay_t<decltype(w)>;
      GVDP_CUDA_CHECK(cudaFuncGetAttributes(&a, growKernel<W>));
    });
    std::printf("%s: growKernel %d registers, %zu bytes of local memory a thread\n", r.name,
                a.numRegs, a.localSizeBytes);
  }
  const char* crowdNames[] = {"none", "same", "others"};
  Stats stats[3][SCENE_COUNT][2];  // crowd, world, cold / hot
  for (int mode = 0; mode < 3; ++mode) {
    const Crowd crowd = static_cast<Crowd>(mode);
    const int threads = 32 * (crowd == Crowd::None ? 1 : 1 + crowdWarps);
    const int grid = crowd == Crowd::None ? 1 : blocks;
    // Launches cycle over the worlds: each follows another world's, so its first growth is cold.
    for (int l = 0; l < (launches + 1) * SCENE_COUNT; ++l) {
      const int self = l % SCENE_COUNT;
      Run& r = runs[self];
      int n = static_cast<int>(r.keys.size());
      GVDP_CUDA_CHECK(cudaMemset(finished, 0, sizeof(int)));
      r.world.visit([&](const auto& w) {
        growKernel<<<grid, threads>>>(w, clipmap, r.deviceKeys, n, crowd, worlds, self, records,
                                      clock, finished, sink);
      });
      GVDP_CUDA_CHECK(cudaGetLastError());
      GVDP_CUDA_CHECK(cudaDeviceSynchronize());
      ClockRecord c;
      GVDP_CUDA_CHECK(cudaMemcpy(&c, clock, sizeof c, cudaMemcpyDeviceToHost));
      GVDP_CUDA_CHECK(
          cudaMemcpy(host.data(), records, sizeof(GrowthRecord) * n, cudaMemcpyDeviceToHost));
      double usPerCycle =
          static_cast<double>(c.ns1 - c.ns0) * 1e-3 / static_cast<double>(c.cycles1 - c.cycles0);
      if (l < SCENE_COUNT) continue;  // the first launch of each: warm-up
      stats[mode][self][0].add(host[0], usPerCycle);
      for (int i = 1; i < n; ++i) stats[mode][self][1].add(host[i], usPerCycle);
    }
  }
  std::printf("%-16s %-6s %-5s %8s %8s %12s %12s %13s %13s\n", "world", "crowd", "code", "growths",
              "rounds/g", "round us med", "round us mean", "growth us med", "growth us mean");
  for (int w = 0; w < SCENE_COUNT; ++w) {
    for (int mode = 0; mode < 3; ++mode) {
      for (int k = 0; k < 2; ++k) {
        const Stats& st = stats[mode][w][k];
        std::printf("%-16s %-6s %-5s %8ld %8.2f %12.2f %12.2f %13.2f %13.2f\n", runs[w].name,
                    crowdNames[mode], k ? "hot" : "cold", st.growths,
                    static_cast<double>(st.rounds) / static_cast<double>(st.growths),
                    median(st.roundUs), mean(st.roundUs), median(st.growthUs), mean(st.growthUs));
      }
    }
  }
  for (Run& r : runs) GVDP_CUDA_CHECK(cudaFree(r.deviceKeys));
  GVDP_CUDA_CHECK(cudaFree(records));
  GVDP_CUDA_CHECK(cudaFree(clock));
  GVDP_CUDA_CHECK(cudaFree(sink));
  GVDP_CUDA_CHECK(cudaFree(finished));
  return 0;
}

}  // namespace
}  // namespace gvdp::detail

int main(int argc, char** argv) {
  return gvdp::detail::experimentMain("gvdp_growth_rounds", gvdp::detail::run, argc, argv);
}
