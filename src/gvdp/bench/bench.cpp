#include "gvdp/bench/bench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "gvdp/base/error.h"
#include "gvdp/base/gpu.h"
#include "gvdp/bench/frame_stats.h"

namespace gvdp::detail {
namespace {

// --scale: dp's frame time at these sizes, on the first scene's walkthrough.
constexpr int SCALE_SIZES[4][2] = {{1280, 720}, {1500, 1000}, {1920, 1080}, {3840, 2160}};

SequenceOptions cellSequence(const BenchOptions& o, const std::string& scene, Movement m,
                             SchedulerKind k) {
  SequenceOptions s;
  if (scene == BENCH_MESH) {
    s.mesh = o.mesh;
    s.lattice = o.lattice;
  } else {
    s.scene = scene;
  }
  s.movement = m;
  s.width = o.width;
  s.height = o.height;
  s.frames = o.warmup + o.frames;
  SchedulerOptions so{o.backend, k, o.poolBricks};
  so.lookahead = o.lookahead;
  so.tailLookahead = o.tailLookahead;
  so.prefetch = o.prefetch;
  so.farPrefetch = o.farPrefetch;
  so.budgetMs = o.budgetMs;
  s.scheduler = resolvedOptions(so);
  return s;
}

BenchOptions scaleOptions(const BenchOptions& o, const int size[2]) {
  BenchOptions so = o;
  so.width = size[0];
  so.height = size[1];
  return so;
}

BenchCell runCell(const BenchOptions& o, const std::string& scene, Movement m, SchedulerKind k) {
  SequenceOptions s = cellSequence(o, scene, m, k);  // checked by validate(BenchOptions)
  std::unique_ptr<Renderer> renderer = makeSequenceRenderer(s);
  Image image;
  BenchCell c{};
  c.scene = worldName(s);
  c.movement = std::string(movementName(m));
  c.scheduler = std::string(schedulerName(k));
  uint64_t bricks = 0, unsampled = 0, samples = 0, lookups = 0, skips = 0;
  uint64_t prefetched = 0,
           prefetchUnused = 0;  // in a measured frame; of its prefetches, in the next
  std::vector<FrameStats> measured;
  for (int f = 0; f < s.frames; ++f) {
    auto t0 = std::chrono::steady_clock::now();
    FrameStats st = renderer->render(poseOf(s, f), image);
    double wall =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (f == 0) c.firstMs = st.ms;
    if (f > o.warmup) prefetchUnused += st.cache.prefetchUnused;
    if (f < o.warmup) continue;
    if (f + 1 < s.frames) prefetched += st.cache.prefetched;
    c.frameMs.push_back(st.ms);
    c.frameWallMs.push_back(wall);
    c.frameBricks.push_back(st.cache.produced + st.cache.empty + st.cache.clear);
    bricks += st.cache.produced + st.cache.clear;
    unsampled += st.cache.unsampled;
    samples += st.cache.samples;
    lookups += st.cache.lookups;
    skips += st.cache.skips;
    c.unfinishedPixels += st.unfinishedPixels;
    measured.push_back(st);
  }
  // The floor: the first measured frames again, from the cache the path has filled.
  std::vector<double> floor;
  for (int f = o.warmup; f < o.warmup + std::min(o.floorFrames, o.frames); ++f)
    floor.push_back(renderer->render(poseOf(s, f), image).ms);
  FrameTimeStats t = frameTimeStats(c.frameMs);
  c.avgFps = t.avgFps;
  c.low1Fps = t.low1Fps;
  c.medianMs = t.medianMs;
  c.p99Ms = t.p99Ms;
  c.medianWallMs = frameTimeStats(c.frameWallMs).medianMs;
  SlowestFrame slowest = slowestFrame(c.frameMs, c.frameBricks);
  c.slowestFrame = o.warmup + static_cast<int>(slowest.index);
  c.slowestBricks = slowest.bricksOverMean;
  c.slowestOverPredicted = slowest.overPredicted;
  c.bricksPerFrame = static_cast<double>(bricks) / static_cast<double>(o.frames);
  c.floorMs = frameTimeStats(floor).medianMs;
  c.overproduction = bricks ? static_cast<double>(unsampled) / static_cast<double>(bricks) : 0.0;
  c.prefetchedPerFrame = static_cast<double>(prefetched) / static_cast<double>(o.frames);
  c.prefetchUsed = prefetched
                       ? 1.0 - static_cast<double>(prefetchUnused) / static_cast<double>(prefetched)
                       : 0.0;
  double rays = static_cast<double>(c.frameMs.size()) * s.width * s.height;
  c.samplesPerRay = static_cast<double>(samples) / rays;
  c.lookupsPerRay = static_cast<double>(lookups) / rays;
  c.skipsPerRay = static_cast<double>(skips) / rays;
  BudgetStats b = budgetStats(measured, o.budgetMs, int64_t{s.width} * s.height);
  c.withinBudget = static_cast<double>(b.framesWithin) / static_cast<double>(measured.size());
  c.coarserPixels = b.coarserShare;
  c.memory = renderer->memory();
  for (const MemoryItem& item : c.memory) c.memoryBytes += item.bytes;
  return c;
}

}  // namespace

void validate(const BenchOptions& o) {
  GVDP_INPUT_CHECK(!o.scenes.empty() && !o.movements.empty() && !o.schedulers.empty(),
                   "empty --scenes, --movements or --schedulers");
  for (const std::string& scene : o.scenes) {
    GVDP_INPUT_CHECK(scene != BENCH_MESH || !o.mesh.empty(), "scene 'mesh' needs --mesh FILE");
    if (scene != BENCH_MESH) findScene(scene);
  }
  GVDP_INPUT_CHECK(o.mesh.empty() || std::count(o.scenes.begin(), o.scenes.end(), BENCH_MESH),
                   "--mesh ", o.mesh, " is not used: add 'mesh' to --scenes");
  // Sizes and memory depend on the scheduler and the frame size, not on the scene or the path.
  auto check = [](const SequenceOptions& s) {
    validate(s);
    checkResources(s);
  };
  for (SchedulerKind k : o.schedulers) check(cellSequence(o, o.scenes[0], o.movements[0], k));
  if (o.scale)
    for (const auto& size : SCALE_SIZES)
      check(cellSequence(scaleOptions(o, size), o.scenes[0], Movement::Walkthrough,
                         SchedulerKind::Dp));
}

BenchResults runBench(const BenchOptions& o,
                      const std::function<void(int, int, const std::string&)>& progress) {
  validate(o);
  BenchResults r;
  r.device = o.backend == Backend::Cuda ? cudaDeviceSummary() : "cpu";
  r.backend = std::string(backendName(o.backend));
  r.width = o.width;
  r.height = o.height;
  r.frames = o.frames;
  r.warmup = o.warmup;
  r.budgetMs = o.budgetMs;
  r.prefetch = prefetchOf(o.prefetch, o.farPrefetch);  // as every pt cell uses it
  r.lookahead = o.lookahead;
  r.tailLookahead = o.tailLookahead;
  r.farPrefetch = o.farPrefetch;
  int total = static_cast<int>(o.scenes.size() * o.movements.size() * o.schedulers.size());
  int done = 0;
  for (const std::string& scene : o.scenes)
    for (Movement m : o.movements)
      for (SchedulerKind k : o.schedulers) {
        r.cells.push_back(runCell(o, scene, m, k));
        const BenchCell& c = r.cells.back();
        char line[512];
        std::snprintf(line, sizeof line,
                      "%s %s %s: %.1f FPS (1%% low %.1f), %.0f bricks/frame, per ray %.1f samples "
                      "%.1f lookups %.1f skips, %.1f%% of bricks unsampled; slowest frame %d "
                      "(%.1fx the mean bricks, %.2fx the time the other frames predict for them)",
                      c.scene.c_str(), c.movement.c_str(), c.scheduler.c_str(), c.avgFps, c.low1Fps,
                      c.bricksPerFrame, c.samplesPerRay, c.lookupsPerRay, c.skipsPerRay,
                      100.0 * c.overproduction, c.slowestFrame, c.slowestBricks,
                      c.slowestOverPredicted);
        std::string text = line;
        if (o.budgetMs >= 0.0) {
          std::snprintf(line, sizeof line,
                        "; %.0f%% of frames within %.1f ms, %.2f%% pixels coarser",
                        100.0 * c.withinBudget, o.budgetMs, 100.0 * c.coarserPixels);
          text += line;
        }
        if (r.prefetch) {
          std::snprintf(line, sizeof line, "; %.0f bricks/frame prefetched, %.1f%% used next",
                        c.prefetchedPerFrame, 100.0 * c.prefetchUsed);
          text += line;
        }
        progress(++done, total, text);
      }
  // Speed-up against sp in the same (scene, movement).
  for (BenchCell& c : r.cells)
    for (const BenchCell& sp : r.cells)
      if (sp.scheduler == "sp" && sp.scene == c.scene && sp.movement == c.movement)
        c.speedupVsSp = c.avgFps / sp.avgFps;
  if (o.scale) {
    for (const auto& wh : SCALE_SIZES) {
      BenchCell c =
          runCell(scaleOptions(o, wh), o.scenes[0], Movement::Walkthrough, SchedulerKind::Dp);
      r.scale.push_back({wh[0], wh[1], c.medianMs, c.avgFps});
      progress(done, total, "scale " + std::to_string(wh[0]) + "x" + std::to_string(wh[1]));
    }
  }
  return r;
}

std::string benchJson(const BenchResults& r) {
  nlohmann::json cells = nlohmann::json::array();
  for (const BenchCell& c : r.cells) {
    nlohmann::json memory = nlohmann::json::object();
    for (const MemoryItem& m : c.memory) memory[m.name] = m.bytes;
    cells.push_back({{"scene", c.scene},
                     {"movement", c.movement},
                     {"scheduler", c.scheduler},
                     {"avg_fps", c.avgFps},
                     {"low1_fps", c.low1Fps},
                     {"median_ms", c.medianMs},
                     {"p99_ms", c.p99Ms},
                     {"bricks_per_frame", c.bricksPerFrame},
                     {"unfinished_pixels", c.unfinishedPixels},
                     {"speedup_vs_sp", c.speedupVsSp},
                     {"floor_ms", c.floorMs},
                     {"samples_per_ray", c.samplesPerRay},
                     {"lookups_per_ray", c.lookupsPerRay},
                     {"skips_per_ray", c.skipsPerRay},
                     {"overproduction", c.overproduction},
                     {"within_budget", c.withinBudget},
                     {"coarser_pixels", c.coarserPixels},
                     {"prefetched_per_frame", c.prefetchedPerFrame},
                     {"prefetch_used", c.prefetchUsed},
                     {"slowest_frame", c.slowestFrame},
                     {"slowest_bricks_x", c.slowestBricks},
                     {"slowest_over_predicted", c.slowestOverPredicted},
                     {"first_ms", c.firstMs},
                     {"median_wall_ms", c.medianWallMs},
                     {"memory_bytes", c.memoryBytes},
                     {"memory", memory},
                     {"frame_ms", c.frameMs},
                     {"frame_wall_ms", c.frameWallMs},
                     {"frame_bricks", c.frameBricks}});
  }
  nlohmann::json scale = nlohmann::json::array();
  for (const BenchScalePoint& p : r.scale)
    scale.push_back({{"width", p.width},
                     {"height", p.height},
                     {"median_ms", p.medianMs},
                     {"avg_fps", p.avgFps}});
  // lookahead, tail_lookahead, prefetch and far_prefetch: pt's settings, its cells' only.
  return nlohmann::json{{"device", r.device},
                        {"backend", r.backend},
                        {"budget_ms", r.budgetMs},
                        {"lookahead", r.lookahead},
                        {"tail_lookahead", r.tailLookahead},
                        {"prefetch", r.prefetch},
                        {"far_prefetch", r.farPrefetch},
                        {"width", r.width},
                        {"height", r.height},
                        {"frames", r.frames},
                        {"warmup", r.warmup},
                        {"cells", cells},
                        {"scale", scale}}
      .dump(1);
}

std::string benchCsv(const BenchResults& r) {
  std::ostringstream s;
  s << "scene,movement,scheduler,avg_fps,low1_fps,median_ms,p99_ms,bricks_per_frame,"
       "unfinished_pixels,speedup_vs_sp,floor_ms,memory_bytes,samples_per_ray,lookups_per_ray,"
       "skips_per_ray,overproduction,within_budget,coarser_pixels,prefetched_per_frame,"
       "prefetch_used,slowest_frame,slowest_bricks_x,slowest_over_predicted,first_ms\n";
  for (const BenchCell& c : r.cells)
    s << c.scene << ',' << c.movement << ',' << c.scheduler << ',' << c.avgFps << ',' << c.low1Fps
      << ',' << c.medianMs << ',' << c.p99Ms << ',' << c.bricksPerFrame << ',' << c.unfinishedPixels
      << ',' << c.speedupVsSp << ',' << c.floorMs << ',' << c.memoryBytes << ',' << c.samplesPerRay
      << ',' << c.lookupsPerRay << ',' << c.skipsPerRay << ',' << c.overproduction << ','
      << c.withinBudget << ',' << c.coarserPixels << ',' << c.prefetchedPerFrame << ','
      << c.prefetchUsed << ',' << c.slowestFrame << ',' << c.slowestBricks << ','
      << c.slowestOverPredicted << ',' << c.firstMs << '\n';
  return s.str();
}

std::string benchMarkdown(const BenchResults& r) {
  // Rows: movements; column groups: scenes, each scheduler's average FPS then SU (vs sp).
  std::vector<std::string> scenes, movements, schedulers;
  auto add = [](std::vector<std::string>& v, const std::string& x) {
    if (std::find(v.begin(), v.end(), x) == v.end()) v.push_back(x);
  };
  std::map<std::string, const BenchCell*> at;
  for (const BenchCell& c : r.cells) {
    add(scenes, c.scene);
    add(movements, c.movement);
    add(schedulers, c.scheduler);
    at[c.scene + "/" + c.movement + "/" + c.scheduler] = &c;
  }
  std::vector<std::string> others;
  for (const std::string& k : schedulers)
    if (k != "sp") others.push_back(k);
  std::ostringstream s;
  s << "| movement |";
  for (const std::string& sc : scenes) {
    for (const std::string& k : schedulers) s << ' ' << sc << ' ' << k << " |";
    for (const std::string& k : others) s << ' ' << sc << " SU " << k << " |";
  }
  s << "\n|---|";
  for (size_t i = 0; i < scenes.size() * (schedulers.size() + others.size()); ++i) s << "---|";
  s << '\n';
  char buf[32];
  for (const std::string& m : movements) {
    s << "| " << m << " |";
    for (const std::string& sc : scenes) {
      for (const std::string& k : schedulers) {
        const BenchCell* c = at[sc + "/" + m + "/" + k];
        std::snprintf(buf, sizeof buf, " %.1f |", c ? c->avgFps : 0.0);
        s << buf;
      }
      for (const std::string& k : others) {
        const BenchCell* c = at[sc + "/" + m + "/" + k];
        std::snprintf(buf, sizeof buf, " %.2f |", c ? c->speedupVsSp : 0.0);
        s << buf;
      }
    }
    s << '\n';
  }
  return s.str();
}

}  // namespace gvdp::detail
