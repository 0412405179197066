// The Table-1 runner (paper 4.1-4.2): every (scene x movement x scheduler) cell renders a
// warm-up, then the measured frames along the path; then the same frames again from the warm
// cache (the render-only floor: almost nothing left to produce). Speed-ups are against sp.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "gvdp/bench/sequence.h"

namespace gvdp::detail {

constexpr const char* BENCH_MESH = "mesh";  // the scene name of `mesh`'s world

struct BenchOptions {
  std::vector<std::string> scenes;  // built-in scenes, and BENCH_MESH for the mesh below
  std::string mesh;                 // a mesh file
  float lattice = 0;
  std::vector<Movement> movements;
  std::vector<SchedulerKind> schedulers;
  Backend backend = Backend::Cpu;
  int width = 1500, height = 1000;
  int frames = 32, warmup = 6, floorFrames = 8;
  uint32_t poolBricks = 0;
  uint32_t lookahead = DEFAULT_LOOKAHEAD;           // pt's
  uint32_t tailLookahead = DEFAULT_TAIL_LOOKAHEAD;  // pt's, in a frame's tail
  uint32_t prefetch = DEFAULT_PREFETCH;             // pt's
  uint32_t farPrefetch = 0;                         // pt's: predicted frames (0: off)
  double budgetMs = NO_BUDGET;                      // every cell's frame-time budget
  bool scale = false;  // frame time against resolution for dp on the first scene
};

struct BenchCell {
  std::string scene, movement, scheduler;
  double avgFps, low1Fps, medianMs, p99Ms, medianWallMs, bricksPerFrame, floorMs, speedupVsSp = 0;
  // Per ray and frame, over the measured frames: samples, brick lookups, empty-space skips.
  double samplesPerRay, lookupsPerRay, skipsPerRay;
  // Bricks produced in a measured frame that no ray of it sampled (a prefetched one: of the next
  // frame), over the bricks produced (bricksPerFrame: those given a slot and the CLEAR ones). Only
  // a brick with a slot carries the timestamp that tells (cache_view.h): an unsampled CLEAR brick
  // is not counted, so this is a lower bound of the work spent on bricks no ray read.
  double overproduction;
  // pt's prefetch: bricks prefetched per frame, and the share of them the next frame sampled.
  double prefetchedPerFrame = 0, prefetchUsed = 0;
  // With a budget: the share of measured frames within it, and of their pixels shown coarser.
  double withinBudget = 0, coarserPixels = 0;
  int64_t unfinishedPixels;
  uint64_t memoryBytes;
  std::vector<double> frameMs;        // CUDA events (GPU) or wall clock (CPU), per measured frame
  std::vector<double> frameWallMs;    // host wall clock around each frame's render() call
  std::vector<uint64_t> frameBricks;  // bricks produced, CLEAR and EMPTY, per measured frame
  // The slowest measured frame (frame_stats.h: slowestFrame): its index on the path (warm-up
  // frames counted), its bricks over the cell's mean, and its time over the time the cell's other
  // frames predict for its bricks.
  int slowestFrame = 0;
  double slowestBricks = 0;
  double slowestOverPredicted = 0;
  // The path's frame 0 (a warm-up frame unless --warmup is 0): from an empty cache, as a render's
  // or a viewer's first frame (a 370 ms stall of pt's there was hidden by the warm-up).
  double firstMs = 0;
  MemoryReport memory;
};

struct BenchScalePoint {
  int width, height;
  double medianMs, avgFps;
};

struct BenchResults {
  std::string device, backend;
  int width, height, frames, warmup;
  double budgetMs;                                           // NO_BUDGET: exact frames
  uint32_t lookahead, tailLookahead, prefetch, farPrefetch;  // pt's (prefetch 0: off)
  std::vector<BenchCell> cells;
  std::vector<BenchScalePoint> scale;
};

// Every cell's sequence (the --scale ones too) through validate() and checkResources(): throws
// InputError before anything runs. runBench() calls it first.
void validate(const BenchOptions& o);

// progress(done, total, line) after every cell.
BenchResults runBench(const BenchOptions& o,
                      const std::function<void(int, int, const std::string&)>& progress);

std::string benchJson(const BenchResults& r);
std::string benchCsv(const BenchResults& r);
std::string benchMarkdown(const BenchResults& r);  // Table 1's shape

}  // namespace gvdp::detail
