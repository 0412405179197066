// The gvdp command line: render, scenes, info, mesh, kdtree (docs/DESIGN.md "Command line
// contract"). Library code throws; this is the one place that turns an exception into a message and
// an exit status: 2 for bad input, 1 for internal failures.
#include <pthread.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <thread>
#include <vector>

#include "gvdp/base/error.h"
#include "gvdp/base/gpu.h"
#include "gvdp/base/parallel.h"
#include "gvdp/bench/bench.h"
#include "gvdp/bench/frame_stats.h"
#include "gvdp/bench/sequence.h"
#include "gvdp/cache/clipmap.h"
#include "gvdp/io/output_paths.h"
#include "gvdp/io/ray_cost_map.h"
#include "gvdp/io/stats.h"
#include "gvdp/io/timeline_export.h"
#include "gvdp/io/video.h"
#include "gvdp/mesh/mesh_io.h"
#include "gvdp/sched/memory_estimate.h"
#include "gvdp/sched/mesh_scene.h"
#include "gvdp/serve/server.h"
#include "mesh_commands.h"

namespace gvdp::detail {
namespace {

Vec3d parseVector(const std::string& text, const char* flag) {
  Vec3d v{};
  char tail = 0;
  GVDP_INPUT_CHECK(std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &v.x, &v.y, &v.z, &tail) == 3, "bad ",
                   flag, " '", text, "' (expected x,y,z)");
  return v;
}

std::string farPrefetchHelp() {
  return "pt: after a frame whose view is closed (the camera inside a sphere, a tree, a hill), "
         "the prefetch marches the next N frames the camera's motion predicts, N 0.." +
         std::to_string(MAX_FAR_PREFETCH) +
         " (default 0: off; 8 moved most of random-spheres' forward exit frame into the frames "
         "before it)";
}

// The pool's accepted sizes: 50 million bricks are 200 GB; 190000 MiB are 49.8 million bricks.
constexpr int64_t MAX_POOL_BRICKS = 50000000;
constexpr int64_t MAX_POOL_MB = 190000;

// Numbers left unset take the backend's default.
struct RenderFlags {
  std::string scene = "perlin", movement = "walkthrough", backend = "auto", scheduler = "sp";
  std::string origin = "0,0,0", out = "out", timeline, video, tiles = "auto", tilePlan = "off";
  std::string mesh;
  float lattice = 0.0f;
  bool reference = false, costMap = false;
  std::optional<int> frames, width, height;
  int videoFps = 30;
  int levels = DEFAULT_LEVELS;
  int lodWidth = 0;
  std::optional<int64_t> poolBricks, poolMb, pendingLaunches, lookahead, tailLookahead, prefetch,
      farPrefetch;
  std::optional<double> budgetMs;
  float fov = DEFAULT_FOV_DEGREES;
};

// The flags of `render`; `timeline` takes them too, but its --out is the picture and it renders
// frames 0..--frame.
void addRenderFlags(CLI::App* cmd, RenderFlags& f, bool timelineCommand = false) {
  cmd->add_option("--scene", f.scene, "scene: " + sceneNames());
  cmd->add_option("--mesh", f.mesh,
                  "a triangle mesh (OFF, PLY, OBJ) as the world instead of --scene: placed at "
                  "the origin, 1 unit long (scripts/get_meshes.sh gets some)");
  cmd->add_option("--lattice", f.lattice,
                  "with --mesh: copies of it every this many units in x and z (default 0: one)");
  cmd->add_option("--movement", f.movement, "camera path: " + movementNames());
  CLI::Option* frames = cmd->add_option("--frames", f.frames,
                                        "frames to render (default: 24 on the GPU, 6 on the CPU)");
  if (timelineCommand) frames->group("");  // hidden: kept only to refuse it (runTimeline)
  cmd->add_option("--width", f.width, "image width (default: 1500 on the GPU, 160 on the CPU)");
  cmd->add_option("--height", f.height, "image height (default: 1000 on the GPU, 100 on the CPU)");
  cmd->add_option("--backend", f.backend, "cpu, cuda or auto (the GPU when there is one)");
  cmd->add_option("--scheduler", f.scheduler,
                  "sp (GigaVoxels loop, default), dp (the paper: dynamic parallelism), pt "
                  "(persistent threads), graph (sp as one CUDA graph, cuda only) or direct (no "
                  "cache, the reference)");
  cmd->add_option("--pending-launches", f.pendingLaunches,
                  "dp: CDP pending-launch buffer, a frame (or tile) launching at most half of it "
                  "on the GPU (task-queue capacity on the CPU), default 65536");
  cmd->add_option("--lookahead", f.lookahead,
                  "pt: missing bricks a stopped ray claims ahead of it, 0.." +
                      std::to_string(MAX_LOOKAHEAD) + " (default " +
                      std::to_string(DEFAULT_LOOKAHEAD) + "; 0: off)");
  cmd->add_option("--tail-lookahead", f.tailLookahead,
                  "pt: at least this lookahead in a frame's tail (at most one ray in " +
                      std::to_string(PT_TAIL_SHARE) + " live), 0.." +
                      std::to_string(MAX_LOOKAHEAD) + " (default " +
                      std::to_string(DEFAULT_TAIL_LOOKAHEAD) + "; 0: --lookahead's)");
  cmd->add_option("--prefetch", f.prefetch,
                  "pt: in each frame's tail, produce the bricks of the next frame the camera's "
                  "motion predicts, marching a ray per N x N pixels, N 0.." +
                      std::to_string(MAX_PREFETCH) + " (default " +
                      std::to_string(DEFAULT_PREFETCH) + ": off; " +
                      std::to_string(FAR_PREFETCH_STRIDE) + " with --far-prefetch)");
  cmd->add_option("--far-prefetch", f.farPrefetch, farPrefetchHelp());
  cmd->add_option("--budget-ms", f.budgetMs,
                  "frame-time budget: past it, rays whose brick is not ready show the nearest "
                  "resident coarser level (produced for the next frames); 0: never wait; default "
                  "off (exact frames)");
  cmd->add_option("--pool-bricks", f.poolBricks,
                  "brick pool slots (default: 500000 = 2 GB on the GPU, 32768 on the CPU; not "
                  "with direct)");
  cmd->add_option("--pool-mb", f.poolMb, "brick pool size in MiB (instead of --pool-bricks)");
  cmd->add_option("--levels", f.levels, "clipmap levels (voxel size doubles per level)");
  cmd->add_option("--fov", f.fov, "horizontal field of view, degrees");
  cmd->add_option("--lod-width", f.lodWidth,
                  "the image width whose pixel footprint picks the levels (default 0: the "
                  "image's, up to " +
                      std::to_string(MAX_LOD_WIDTH) + "; the clipmap grows as its cube)");
  cmd->add_option("--origin", f.origin, "x,y,z added to the scene's start position");
  cmd->add_option("--tiles", f.tiles,
                  "auto (default: one tile while the frame's bricks fit the pool and its rays "
                  "the payload, else exact tiles), off (a frame that overflows degrades) or N "
                  "(an N x N grid)");
  cmd->add_option("--tile-plan", f.tilePlan,
                  "on (default: a frame that overflows is cut into tiles planned by the "
                  "importance pre-pass) or off (into quadrants, recursively)")
      ->check(CLI::IsMember({"on", "off"}));
  if (timelineCommand) return;
  cmd->add_option("--out", f.out, "output directory for frame_NNNN.png and stats.json");
  cmd->add_flag("--reference", f.reference,
                "with --mesh: also the ray cast of the triangles (reference_NNNN.png) and each "
                "frame's PSNR against it");
  cmd->add_flag("--cost-map", f.costMap,
                "also each pixel's brick lookups, samples and stops (cost_NNNN.png, a heat map "
                "each, and their quantiles in stats.json)");
  cmd->add_option("--timeline", f.timeline,
                  "also record every frame's GPU-cores timeline: DIR/timeline_NNNN.png and .json");
  cmd->add_option("--video", f.video,
                  "also encode the frames into a video file (H.264; needs the ffmpeg command)");
  cmd->add_option("--video-fps", f.videoFps, "the video's frame rate (default 30)");
}

// "auto" is the GPU when there is one; "cuda" must find a device now, before any output is made.
Backend resolveBackend(const std::string& name) {
  if (name == "auto") return cudaDeviceAvailable() ? Backend::Cuda : Backend::Cpu;
  Backend backend = parseBackend(name);
  requireBackend(backend);
  return backend;
}

// The pool in bricks from --pool-bricks or --pool-mb (0: the backend's default). The user's
// numbers are range-checked before any arithmetic on them.
uint32_t poolBricksFrom(const std::optional<int64_t>& bricks, const std::optional<int64_t>& mb) {
  GVDP_INPUT_CHECK(!bricks || !mb, "give --pool-bricks or --pool-mb, not both");
  if (bricks) {
    GVDP_INPUT_CHECK(*bricks >= 1 && *bricks <= MAX_POOL_BRICKS, "bad --pool-bricks ", *bricks,
                     " (expected 1..", MAX_POOL_BRICKS, ")");
    return static_cast<uint32_t>(*bricks);
  }
  if (!mb) return 0;
  GVDP_INPUT_CHECK(*mb >= 1 && *mb <= MAX_POOL_MB, "bad --pool-mb ", *mb, " (expected 1..",
                   MAX_POOL_MB, ")");
  return static_cast<uint32_t>(*mb * (int64_t{1} << 20) / (BRICK_SAMPLE_COUNT * sizeof(Rgba8)));
}

// The flag the pool was sized with, to name it when the configuration does not fit.
std::string poolFlag(const RenderFlags& f) {
  if (f.poolMb) return "--pool-mb " + std::to_string(*f.poolMb);
  if (f.poolBricks) return "--pool-bricks " + std::to_string(*f.poolBricks);
  return "";
}

// Flags the chosen scheduler has no use for are refused, not ignored.
void refuseUnusedFlags(const RenderFlags& f, SchedulerKind kind) {
  bool direct = kind == SchedulerKind::Direct;
  GVDP_INPUT_CHECK(!direct || !f.poolBricks, "--pool-bricks ", f.poolBricks.value_or(0),
                   " is not used by scheduler direct (it has no brick cache)");
  GVDP_INPUT_CHECK(!direct || !f.poolMb, "--pool-mb ", f.poolMb.value_or(0),
                   " is not used by scheduler direct (it has no brick cache)");
  GVDP_INPUT_CHECK(kind == SchedulerKind::Dp || !f.pendingLaunches, "--pending-launches ",
                   f.pendingLaunches.value_or(0), " is used by scheduler dp only, not by ",
                   schedulerName(kind));
  GVDP_INPUT_CHECK(kind == SchedulerKind::Pt || !f.lookahead, "--lookahead ",
                   f.lookahead.value_or(0), " is used by scheduler pt only, not by ",
                   schedulerName(kind));
  GVDP_INPUT_CHECK(kind == SchedulerKind::Pt || !f.tailLookahead, "--tail-lookahead ",
                   f.tailLookahead.value_or(0), " is used by scheduler pt only, not by ",
                   schedulerName(kind));
  GVDP_INPUT_CHECK(kind == SchedulerKind::Pt || !f.prefetch, "--prefetch ", f.prefetch.value_or(0),
                   " is used by scheduler pt only, not by ", schedulerName(kind));
  GVDP_INPUT_CHECK(kind == SchedulerKind::Pt || !f.farPrefetch, "--far-prefetch ",
                   f.farPrefetch.value_or(0), " is used by scheduler pt only, not by ",
                   schedulerName(kind));
  GVDP_INPUT_CHECK(!direct || !f.budgetMs, "--budget-ms ", f.budgetMs.value_or(0.0),
                   " is not used by scheduler direct (it waits for no brick)");
}

double budgetFrom(const std::optional<double>& ms) {
  if (!ms) return NO_BUDGET;
  GVDP_INPUT_CHECK(*ms >= 0.0 && *ms <= MAX_BUDGET_MS, "bad --budget-ms ", *ms, " (expected 0..",
                   MAX_BUDGET_MS, ")");
  return *ms;
}

uint32_t lookaheadFrom(const std::optional<int64_t>& n, const char* flag = "--lookahead",
                       uint32_t otherwise = DEFAULT_LOOKAHEAD) {
  if (!n) return otherwise;
  GVDP_INPUT_CHECK(*n >= 0 && *n <= MAX_LOOKAHEAD, "bad ", flag, " ", *n, " (expected 0..",
                   MAX_LOOKAHEAD, ")");
  return static_cast<uint32_t>(*n);
}

// --prefetch N; unset, the default as a far prefetch (--far-prefetch `far`) leaves it (prefetchOf).
uint32_t prefetchFrom(const std::optional<int64_t>& n, const std::optional<int64_t>& far) {
  if (!n) return prefetchOf(DEFAULT_PREFETCH, far && *far > 1 ? static_cast<uint32_t>(*far) : 0u);
  GVDP_INPUT_CHECK(*n >= 0 && *n <= MAX_PREFETCH, "bad --prefetch ", *n, " (expected 0..",
                   MAX_PREFETCH, ")");
  return static_cast<uint32_t>(*n);
}

// --far-prefetch N, with the prefetch it extends (`prefetch`: the ray spacing, 0: off).
uint32_t farPrefetchFrom(const std::optional<int64_t>& n, uint32_t prefetch) {
  if (!n) return 0;
  GVDP_INPUT_CHECK(*n >= 0 && *n <= MAX_FAR_PREFETCH, "bad --far-prefetch ", *n, " (expected 0..",
                   MAX_FAR_PREFETCH, " predicted frames; 0: off)");
  GVDP_INPUT_CHECK(*n <= 1 || prefetch != 0, "--far-prefetch ", *n,
                   " needs pt's prefetch, which --prefetch 0 turns off");
  return static_cast<uint32_t>(*n);
}

uint32_t pendingLaunchesFrom(const std::optional<int64_t>& n) {
  if (!n) return 0;
  GVDP_INPUT_CHECK(*n >= 1 && *n <= (1 << 24), "bad --pending-launches ", *n,
                   " (expected 1..16777216)");
  return static_cast<uint32_t>(*n);
}

// Every input check, the backend's device and memory included: nothing is written before.
SequenceOptions toOptions(const RenderFlags& f) {
  SequenceOptions o;
  o.scene = f.scene;
  o.mesh = f.mesh;
  o.lattice = f.lattice;
  GVDP_INPUT_CHECK(f.lattice == 0.0f || !f.mesh.empty(), "--lattice ", f.lattice,
                   " needs --mesh (it repeats a mesh)");
  GVDP_INPUT_CHECK(!f.reference || !f.mesh.empty(),
                   "--reference needs --mesh (the ray cast of its triangles)");
  o.movement = parseMovement(f.movement);
  if (!o.mesh.empty()) readMesh(o.mesh);  // a missing or malformed file before any output
  o.scheduler.backend = resolveBackend(f.backend);
  bool gpu = o.scheduler.backend == Backend::Cuda;
  o.scheduler.kind = parseScheduler(f.scheduler);
  GVDP_INPUT_CHECK(o.scheduler.kind != SchedulerKind::Graph || gpu,
                   "scheduler 'graph' runs on the cuda backend only (a CUDA graph of the sp loop)");
  refuseUnusedFlags(f, o.scheduler.kind);
  o.frames = f.frames.value_or(gpu ? 24 : 6);
  o.width = f.width.value_or(gpu ? 1500 : 160);
  o.height = f.height.value_or(gpu ? 1000 : 100);
  o.levels = f.levels;
  o.scheduler.poolBricks = poolBricksFrom(f.poolBricks, f.poolMb);
  o.scheduler.pendingLaunches = pendingLaunchesFrom(f.pendingLaunches);
  o.scheduler.lookahead = lookaheadFrom(f.lookahead);
  o.scheduler.tailLookahead =
      lookaheadFrom(f.tailLookahead, "--tail-lookahead", DEFAULT_TAIL_LOOKAHEAD);
  o.scheduler.prefetch = prefetchFrom(f.prefetch, f.farPrefetch);
  o.scheduler.farPrefetch = farPrefetchFrom(f.farPrefetch, o.scheduler.prefetch);
  o.scheduler.budgetMs = budgetFrom(f.budgetMs);
  o.fovDegrees = f.fov;
  o.lodWidth = f.lodWidth;
  o.origin = parseVector(f.origin, "--origin");
  o.tiles.mode = parseTileMode(f.tiles, &o.tiles.grid);
  o.tiles.plan = f.tilePlan == "on";
  o.scheduler.timeline = !f.timeline.empty();
  GVDP_INPUT_CHECK(!f.costMap || o.scheduler.kind != SchedulerKind::Direct,
                   "--cost-map needs a cached scheduler (sp, dp, pt or graph): 'direct' makes no "
                   "brick lookups");
  o.scheduler.rayCosts = f.costMap;
  o.scheduler = resolvedOptions(o.scheduler);
  validate(o);
  checkResources(o, poolFlag(f));
  return o;
}

// A picture's title: "pt on cuda, perlin frame 12, 1500x1000".
std::string frameTitle(const SequenceOptions& o, int index) {
  return std::string(schedulerName(o.scheduler.kind)) + " on " +
         std::string(backendName(o.scheduler.backend)) + ", " + worldName(o) + " frame " +
         std::to_string(index) + ", " + std::to_string(o.width) + "x" + std::to_string(o.height);
}

void writeTimeline(const FrameStats& s, const std::string& dir, int index,
                   const SequenceOptions& o) {
  char base[64];
  std::snprintf(base, sizeof base, "/timeline_%04d", index);
  const TimelineCapture& t = s.timeline;
  writePng(timelineImage(t.records, t.lanes, frameTitle(o, index)), dir + base + ".png");
  std::ofstream json(dir + base + ".json");
  json << chromeTraceJson(t.records, t.lanes);
  GVDP_INPUT_CHECK(json.good(), "cannot write '", dir, base, ".json'");
  std::printf("           %s%s\n", timelineSummary(timelineStats(t.records, t.lanes)).c_str(),
              t.overflow ? " (records overflowed)" : "");
}

void printMemoryReport(const MemoryReport& memory) {
  if (memory.empty()) return;
  std::printf("memory:");
  for (const MemoryItem& m : memory)
    std::printf(" %s %.1f MB,", m.name.c_str(), static_cast<double>(m.bytes) / 1e6);
  std::printf(" total %.1f MB\n", static_cast<double>(memoryTotal(memory)) / 1e6);
}

// A tiled frame's progress on stderr: a bar redrawn in place on a terminal, else a line per
// tenth of the tiles known.
struct TileBar {
  int lastTenth = -1;
  void operator()(int done, int known) {
    if (known <= 1) return;
    int tenth = 10 * done / known;
    if (isatty(2)) {
      char bar[21];
      int filled = 20 * done / known;
      for (int i = 0; i < 20; ++i) bar[i] = i < filled ? '#' : '.';
      bar[20] = 0;
      std::fprintf(stderr, "\r  tiles [%s] %d / %d%s", bar, done, known, done == known ? "\n" : "");
    } else if (tenth != lastTenth) {
      std::fprintf(stderr, "  tiles %d / %d\n", done, known);
    }
    lastTenth = done == known ? -1 : tenth;
  }
};

int runRender(const RenderFlags& flags) {
  SequenceOptions o = toOptions(flags);
  GVDP_INPUT_CHECK(flags.videoFps >= 1 && flags.videoFps <= 240, "bad --video-fps ", flags.videoFps,
                   " (expected 1..240)");
  OutputPaths outputs;
  outputs.directory(flags.out);
  if (!flags.timeline.empty()) outputs.directory(flags.timeline);
  if (!flags.video.empty()) outputs.file(flags.video);
  std::optional<VideoWriter> video;
  if (!flags.video.empty()) video.emplace(flags.video, o.width, o.height, flags.videoFps);
  outputs.keep();
  const std::string& dir = flags.out;
  std::fprintf(stderr, "gvdp: %s, %s, %dx%d, %d frames, scheduler %s on %s\n", worldName(o).c_str(),
               std::string(movementName(o.movement)).c_str(), o.width, o.height, o.frames,
               std::string(schedulerName(o.scheduler.kind)).c_str(),
               o.scheduler.backend == Backend::Cuda ? cudaDeviceSummary().c_str() : "cpu");
  std::vector<FrameStats> frames;
  std::vector<RayCostSummary> costs;
  // The reference: the same mesh, its tree built on the CPU, ray cast on the CPU.
  std::shared_ptr<const MeshScene> reference;
  if (flags.reference) reference = MeshScene::load(o.mesh, o.lattice, Backend::Cpu);
  MemoryReport memory = renderSequence(
      o,
      [&](const Image& image, const FrameStats& s) {
        char name[32];
        std::snprintf(name, sizeof name, "/frame_%04d.png", s.index);
        writePng(image, dir + name);
        if (reference) {
          Image ray;
          reference->renderReference(frameOf(o, s.index), ray);
          std::snprintf(name, sizeof name, "/reference_%04d.png", s.index);
          writePng(ray, dir + name);
          std::printf("frame %4d  PSNR against the ray cast %.2f dB\n", s.index, psnr(image, ray));
        }
        if (video) video->add(image);
        if (!flags.timeline.empty()) writeTimeline(s, flags.timeline, s.index, o);
        if (!s.rayCosts.empty()) {
          std::snprintf(name, sizeof name, "/cost_%04d.png", s.index);
          costs.push_back(writeRayCostMap(s.rayCosts, frameTitle(o, s.index), dir + name));
        }
        frames.push_back(s);
        frames.back().rayCosts = {};  // the maps are in the pictures
        std::printf(
            "frame %4d  %9.2f ms  %8.1f FPS  passes %3d  bricks %6llu  clear %6llu  unfinished "
            "%lld%s%s\n",
            s.index, s.ms, 1000.0 / std::max(s.ms, 1e-6), s.passes,
            static_cast<unsigned long long>(s.cache.produced),
            static_cast<unsigned long long>(s.cache.clear),
            static_cast<long long>(s.unfinishedPixels), s.degraded ? "  degraded" : "",
            s.cache.coarser ? ("  coarser " + std::to_string(s.cache.coarser)).c_str() : "");
        if (s.launches && o.scheduler.kind == SchedulerKind::Pt)
          std::printf("           tasks %llu  relaunched rays %llu  longest wait list %llu%s\n",
                      static_cast<unsigned long long>(s.launches),
                      static_cast<unsigned long long>(s.relaunchedRays),
                      static_cast<unsigned long long>(s.longestWaitList), s.spike ? "  spike" : "");
        else if (s.launches || s.launchFailures || s.deferred || s.sweptPixels)
          std::printf("           launches %llu  refused %llu  deferred %llu  swept %lld\n",
                      static_cast<unsigned long long>(s.launches),
                      static_cast<unsigned long long>(s.launchFailures),
                      static_cast<unsigned long long>(s.deferred),
                      static_cast<long long>(s.sweptPixels));
        if (!s.rayCosts.empty()) std::printf("           %s\n", rayCostLine(costs.back()).c_str());
        if (s.tiles > 1 || s.tileSplits || s.lodBias)
          std::printf(
              "           tiles %d  split on overflow %d  plans %d (%.1f ms)  lod bias %d\n",
              s.tiles, s.tileSplits, s.tilePlans, s.planMs, s.lodBias);
        std::fflush(stdout);
      },
      TileBar{});
  writeStatsJson(dir + "/stats.json", o, frames, memory, costs);
  if (video)
    std::printf("wrote %s (%d frames at %d FPS)\n", flags.video.c_str(), video->close(),
                flags.videoFps);
  printMemoryReport(memory);
  double total = 0.0;
  for (const FrameStats& s : frames) total += s.ms;
  double mean = total / static_cast<double>(frames.size());
  std::printf(
      "average %.2f ms per frame (%.1f FPS) over %zu frames; wrote %s/frame_*.png, %s/stats.json\n",
      mean, 1000.0 / std::max(mean, 1e-6), frames.size(), dir.c_str(), dir.c_str());
  if (o.scheduler.budgetMs >= 0.0) {
    BudgetStats b = budgetStats(frames, o.scheduler.budgetMs, o.width * o.height);
    std::printf("budget %.2f ms: %zu of %zu frames within it, %.2f%% of pixels shown coarser\n",
                o.scheduler.budgetMs, b.framesWithin, frames.size(), 100.0 * b.coarserShare);
  }
  return 0;
}

// gvdp timeline: renders frames 0..K and draws the timeline of frame K, or (again) of frame K's
// pose rendered once more from the cache frame K left: the render-only floor (`gvdp bench`'s).
int runTimeline(const RenderFlags& flags, int frame, bool again, const std::string& png,
                const std::string& trace, const std::string& costMap) {
  GVDP_INPUT_CHECK(!flags.frames,
                   "timeline takes --frame K (it renders frames 0..K), not --frames ",
                   flags.frames.value_or(0));
  GVDP_INPUT_CHECK(frame >= 0 && frame <= 100000, "bad --frame ", frame, " (expected 0..100000)");
  RenderFlags f = flags;
  f.frames = frame + 1;
  f.costMap = !costMap.empty();
  SequenceOptions o = toOptions(f);
  o.again = again ? 1 : 0;
  o.scheduler.timeline = true;
  OutputPaths outputs;
  outputs.file(png);
  if (!trace.empty()) outputs.file(trace);
  if (!costMap.empty()) outputs.file(costMap);
  outputs.keep();
  FrameStats last;
  renderSequence(o, [&](const Image&, const FrameStats& s) { last = s; });
  const TimelineCapture& t = last.timeline;
  std::string title = std::string(schedulerName(o.scheduler.kind)) + " on " +
                      std::string(backendName(o.scheduler.backend)) + ", " + worldName(o) + " " +
                      std::string(movementName(o.movement)) + " frame " + std::to_string(frame) +
                      (again ? " again" : "") + ", " + std::to_string(o.width) + "x" +
                      std::to_string(o.height) + ", " + std::to_string(last.ms) + " ms";
  writePng(timelineImage(t.records, t.lanes, title), png);
  if (!trace.empty()) {
    std::ofstream json(trace);
    json << chromeTraceJson(t.records, t.lanes);
    GVDP_INPUT_CHECK(json.good(), "cannot write '", trace, "'");
  }
  std::printf("frame %d%s: %.2f ms; %s%s\nwrote %s%s%s\n", frame, again ? " again" : "", last.ms,
              timelineSummary(timelineStats(t.records, t.lanes)).c_str(),
              t.overflow ? " (records overflowed)" : "", png.c_str(), trace.empty() ? "" : ", ",
              trace.c_str());
  if (!costMap.empty()) {
    RayCostSummary c = writeRayCostMap(last.rayCosts, title, costMap);
    std::printf("%s\nwrote %s\n", rayCostLine(c).c_str(), costMap.c_str());
  }
  return 0;
}

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(s);
  while (std::getline(in, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

// Numbers left unset take the backend's default.
struct BenchFlags {
  std::string scenes = "perlin,fbm,forest,random-spheres,aligned-spheres";
  std::string movements = "walkthrough,forward,backward,sideways,spinning";
  std::string schedulers = "sp,dp,pt", backend = "auto", out = "results.json", csv, markdown;
  std::string mesh;
  float lattice = 0.0f;
  std::optional<int> frames, warmup, width, height;
  std::optional<int64_t> poolBricks, lookahead, tailLookahead, prefetch, farPrefetch;
  std::optional<double> budgetMs;
  bool scale = false;
};

void writeText(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  GVDP_INPUT_CHECK(out.good(), "cannot write '", path, "'");
}

// A list that names an item twice would run its cells twice.
void refuseDuplicates(const std::vector<std::string>& names, const char* flag) {
  for (size_t i = 0; i < names.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      GVDP_INPUT_CHECK(names[i] != names[j], "bad ", flag, ": '", names[i], "' is listed twice");
}

std::vector<SchedulerKind> benchSchedulers(const std::string& list, bool gpu) {
  std::vector<SchedulerKind> kinds;
  std::vector<std::string> names;
  for (const std::string& k : splitList(list)) {
    SchedulerKind kind = parseScheduler(k);
    GVDP_INPUT_CHECK(kind != SchedulerKind::Direct, "bad --schedulers '", k,
                     "' (direct has no cache to benchmark; use sp, dp, pt, graph)");
    GVDP_INPUT_CHECK(kind != SchedulerKind::Graph || gpu, "bad --schedulers '", k,
                     "' (graph runs on the cuda backend only)");
    kinds.push_back(kind);
    names.push_back(std::string(schedulerName(kind)));
  }
  refuseDuplicates(names, "--schedulers");
  return kinds;
}

// "mesh" names the --mesh file's world.
std::vector<std::string> benchScenes(const std::string& list) {
  std::vector<std::string> scenes;
  for (const std::string& s : splitList(list))
    scenes.push_back(s == BENCH_MESH ? s : std::string(findScene(s).name));
  refuseDuplicates(scenes, "--scenes");
  return scenes;
}

std::vector<Movement> benchMovements(const std::string& list) {
  std::vector<Movement> movements;
  std::vector<std::string> names;
  for (const std::string& m : splitList(list)) {
    movements.push_back(parseMovement(m));
    names.push_back(std::string(movementName(movements.back())));
  }
  refuseDuplicates(names, "--movements");
  return movements;
}

// Every input check of `bench`, the memory of every cell included: nothing runs before.
BenchOptions benchOptions(const BenchFlags& f) {
  BenchOptions o;
  o.backend = resolveBackend(f.backend);
  bool gpu = o.backend == Backend::Cuda;
  // --mesh alone: the mesh's cells only.
  o.scenes =
      benchScenes(!f.mesh.empty() && f.scenes == BenchFlags{}.scenes ? BENCH_MESH : f.scenes);
  o.mesh = f.mesh;
  o.lattice = f.lattice;
  o.movements = benchMovements(f.movements);
  o.schedulers = benchSchedulers(f.schedulers, gpu);
  GVDP_INPUT_CHECK(!f.scale || !f.width, "--width ", f.width.value_or(0),
                   " is not used with --scale (it measures 1280x720 to 3840x2160)");
  GVDP_INPUT_CHECK(!f.scale || !f.height, "--height ", f.height.value_or(0),
                   " is not used with --scale (it measures 1280x720 to 3840x2160)");
  o.width = f.width.value_or(gpu ? 1500 : 160);
  o.height = f.height.value_or(gpu ? 1000 : 100);
  o.frames = f.frames.value_or(gpu ? 32 : 6);
  o.warmup = f.warmup.value_or(gpu ? 6 : 2);
  GVDP_INPUT_CHECK(o.frames >= 1 && o.frames <= 100000, "bad --frames ", o.frames,
                   " (expected 1..100000)");
  GVDP_INPUT_CHECK(o.warmup >= 0 && o.warmup <= 100000, "bad --warmup ", o.warmup,
                   " (expected 0..100000)");
  o.poolBricks = poolBricksFrom(f.poolBricks, std::nullopt);
  o.lookahead = lookaheadFrom(f.lookahead);
  o.tailLookahead = lookaheadFrom(f.tailLookahead, "--tail-lookahead", DEFAULT_TAIL_LOOKAHEAD);
  o.prefetch = prefetchFrom(f.prefetch, f.farPrefetch);
  o.farPrefetch = farPrefetchFrom(f.farPrefetch, o.prefetch);
  o.budgetMs = budgetFrom(f.budgetMs);
  o.scale = f.scale;
  validate(o);
  return o;
}

int runBenchCommand(const BenchFlags& f) {
  BenchOptions o = benchOptions(f);
  // Every output is checked before the long run, not after it.
  OutputPaths outputs;
  outputs.file(f.out);
  if (!f.csv.empty()) outputs.file(f.csv);
  if (!f.markdown.empty()) outputs.file(f.markdown);
  outputs.keep();
  BenchResults r = runBench(o, [](int done, int total, const std::string& line) {
    int bar = total ? 30 * done / total : 30;
    std::fprintf(stderr, "\r[%-30s] %d/%d %s\x1b[K", std::string(bar, '#').c_str(), done, total,
                 line.c_str());
    if (done == total) std::fprintf(stderr, "\n");
  });
  writeText(f.out, benchJson(r));
  if (!f.csv.empty()) writeText(f.csv, benchCsv(r));
  if (!f.markdown.empty()) writeText(f.markdown, benchMarkdown(r));
  std::printf("%s", benchMarkdown(r).c_str());
  std::printf("wrote %s\n", f.out.c_str());
  return 0;
}

struct ServeFlags {
  std::string scene = "perlin", scheduler = "pt", backend = "auto", host = "127.0.0.1";
  std::string path = "free";
  int port = 8080, quality = 80;
  std::optional<int> width, height;
  std::optional<double> budgetMs;
  std::optional<int64_t> poolBricks;
};

// Every input check of `serve` (the first view's memory included) before the port is bound.
ServeOptions serveOptions(const ServeFlags& f) {
  ServeOptions o;
  GVDP_INPUT_CHECK(f.port >= 0 && f.port <= 65535, "bad --port ", f.port, " (expected 0..65535)");
  GVDP_INPUT_CHECK(f.quality >= 1 && f.quality <= 100, "bad --quality ", f.quality,
                   " (expected 1..100)");
  o.host = f.host;
  o.port = f.port;
  LoopOptions& loop = o.loop;
  loop.backend = resolveBackend(f.backend);
  bool gpu = loop.backend == Backend::Cuda;
  ViewSettings first;
  first.width = gpu ? 1500 : 320;
  first.height = gpu ? 1000 : 200;
  auto text = [](const auto& v) {
    return v ? std::optional<std::string>(std::to_string(*v)) : std::nullopt;
  };
  loop.view = parseViewSettings(
      first, loop.backend,
      {f.scene, f.scheduler, text(f.width), text(f.height), text(f.budgetMs), f.path});
  loop.poolBricks = poolBricksFrom(f.poolBricks, std::nullopt);
  loop.quality = f.quality;
  // Encoders: half the hardware threads, 1..8. On the H100 machine's 16, 4 of them dropped 10%
  // of perlin's 168 frames a second (all busy, or finishing after a newer frame); 8 keep up.
  loop.encoders = std::clamp(static_cast<int>(std::thread::hardware_concurrency()) / 2, 1, 8);
  SequenceOptions check;
  check.scene = loop.view.scene;
  check.scheduler.backend = loop.backend;
  check.scheduler.kind = loop.view.scheduler;
  check.scheduler.poolBricks = loop.poolBricks;
  check.scheduler = resolvedOptions(check.scheduler);
  check.width = loop.view.width;
  check.height = loop.view.height;
  validate(check);
  checkResources(check);
  return o;
}

// Serves until SIGINT or SIGTERM, which a thread of its own waits for (the signals are blocked in
// every other thread), so the server stops from ordinary code, not from a signal handler.
int runServe(const ServeFlags& flags) {
  sigset_t stopSignals;  // blocked before any thread is made: they all inherit the mask
  sigemptyset(&stopSignals);
  sigaddset(&stopSignals, SIGINT);
  sigaddset(&stopSignals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stopSignals, nullptr);
  ServeOptions o = serveOptions(flags);
  std::signal(SIGPIPE, SIG_IGN);  // a client that goes away mid-frame
  ViewerServer server(o);
  std::printf("gvdp: serving %s with %s on %s at http://%s:%d/ (Ctrl-C stops)\n",
              o.loop.view.scene.c_str(), std::string(schedulerName(o.loop.view.scheduler)).c_str(),
              o.loop.backend == Backend::Cuda ? cudaDeviceSummary().c_str() : "the cpu",
              o.host.c_str(), server.port());
  std::fflush(stdout);
  std::thread waiter([&] {
    int signal = 0;
    sigwait(&stopSignals, &signal);
    server.stop();
  });
  server.run();
  pthread_kill(waiter.native_handle(), SIGTERM);  // wakes the waiter if no signal came
  waiter.join();
  std::printf("gvdp: stopped\n");
  return 0;
}

int runScenes() {
  for (const SceneInfo& s : allScenes())
    std::printf("%-16s %s\n%16s voxel size %.4g, start (%.1f, %.1f, %.1f), %.2f units/frame\n",
                std::string(s.name).c_str(), std::string(s.description).c_str(), "",
                s.world.voxelSize0(), s.start.position.x, s.start.position.y, s.start.position.z,
                s.speed);
  return 0;
}

// Bytes of every structure at a configuration (memory_estimate.h): the items of sp, dp and pt,
// then each scheduler's total.
void printMemory(const char* label, Backend backend, int width, int height) {
  SequenceOptions o;
  o.width = width;
  o.height = height;
  o.scheduler.backend = backend;
  FrameSetup frame = frameOf(o, 0);
  std::printf("memory at %s (%dx%d, clipmap %d^3 x %d levels, pool %u bricks):\n", label, width,
              height, clipmapOf(frame).width, o.levels, poolBricksOf(o.scheduler));
  MemoryReport items;
  std::string totals;
  for (SchedulerKind kind : {SchedulerKind::Sp, SchedulerKind::Dp, SchedulerKind::Pt}) {
    o.scheduler.kind = kind;
    MemoryReport m = memoryEstimate(o.scheduler, frame);
    for (const MemoryItem& item : m)
      if (std::none_of(items.begin(), items.end(),
                       [&](const MemoryItem& i) { return i.name == item.name; }))
        items.push_back(item);
    char total[64];
    std::snprintf(total, sizeof total, "%s%s %.1f MB", totals.empty() ? "" : ", ",
                  std::string(schedulerName(kind)).c_str(),
                  static_cast<double>(memoryTotal(m)) / 1e6);
    totals += total;
  }
  for (const MemoryItem& i : items)
    std::printf("  %-28s %10.1f MB\n", i.name.c_str(), static_cast<double>(i.bytes) / 1e6);
  std::printf("  total: %s%s\n", totals.c_str(),
              backend == Backend::Cuda ? " (dp adds CUDA's pending-launch buffer)" : "");
}

int runInfo() {
  std::printf("gvdp %s\n", GVDP_VERSION);
  std::printf("cuda backend: %s\n", cudaBuilt() ? "built (sm_" GVDP_CUDA_ARCHS ")" : "not built");
  std::printf("devices: %s\n", cudaDeviceSummary().c_str());
  std::printf("cpu threads: %d\n", ThreadPool::global().size());
  std::printf("scenes: %s\nmovements: %s\n", sceneNames().c_str(), movementNames().c_str());
  printMemory("the GPU defaults", Backend::Cuda, 1500, 1000);
  printMemory("the CPU defaults", Backend::Cpu, 160, 100);
  return 0;
}

int run(int argc, char** argv) {
  CLI::App app{"gvdp: GigaVoxels DP, walkthroughs of large procedural voxel worlds"};
  app.require_subcommand(1);
  RenderFlags render;
  CLI::App* renderCmd = app.add_subcommand("render", "render a camera path to PNG frames");
  addRenderFlags(renderCmd, render);
  RenderFlags timeline;
  int timelineFrame = 5;
  std::string timelinePng = "timeline.png", timelineTrace, timelineCostMap;
  bool timelineAgain = false;
  CLI::App* timelineCmd =
      app.add_subcommand("timeline", "draw the GPU-cores timeline of one frame (paper Fig. 5)");
  addRenderFlags(timelineCmd, timeline, true);
  timelineCmd->add_option("--frame", timelineFrame,
                          "the frame to record (frames before it warm up)");
  timelineCmd->add_option("--out", timelinePng, "timeline picture (default timeline.png)");
  timelineCmd->add_option("--trace", timelineTrace, "Chrome trace-event JSON (Perfetto)");
  timelineCmd->add_option("--cost-map", timelineCostMap,
                          "also the frame's cost map: each pixel's brick lookups, samples and "
                          "stops (a PNG; its counting adds a little to the frame timed)");
  timelineCmd->add_flag("--again", timelineAgain,
                        "record the frame's pose rendered once more, from the cache the frame "
                        "filled (the render-only floor)");
  BenchFlags bench;
  CLI::App* benchCmd =
      app.add_subcommand("bench", "the paper's Table 1: scenes x movements x schedulers");
  benchCmd->add_option("--scenes", bench.scenes,
                       "comma-separated (default: all five; 'mesh': the --mesh file)");
  benchCmd->add_option("--mesh", bench.mesh, "a mesh file, the world of the scene 'mesh'");
  benchCmd->add_option("--lattice", bench.lattice, "the mesh's copies (see render --lattice)");
  benchCmd->add_option("--movements", bench.movements, "comma-separated (default: all five)");
  benchCmd->add_option("--schedulers", bench.schedulers,
                       "comma-separated (default: sp,dp,pt; graph: cuda only)");
  benchCmd->add_option("--backend", bench.backend, "cpu, cuda or auto");
  benchCmd->add_option("--frames", bench.frames, "measured frames per cell (GPU 32, CPU 6)");
  benchCmd->add_option("--warmup", bench.warmup, "frames before measuring (GPU 6, CPU 2)");
  benchCmd->add_option("--width", bench.width, "image width (GPU 1500, CPU 160)");
  benchCmd->add_option("--height", bench.height, "image height (GPU 1000, CPU 100)");
  benchCmd->add_option("--pool-bricks", bench.poolBricks, "brick pool slots");
  benchCmd->add_option(
      "--lookahead", bench.lookahead,
      "pt's lookahead in bricks (default " + std::to_string(DEFAULT_LOOKAHEAD) + ")");
  benchCmd->add_option("--tail-lookahead", bench.tailLookahead,
                       "pt's lookahead in a frame's tail (default " +
                           std::to_string(DEFAULT_TAIL_LOOKAHEAD) +
                           "; see render --tail-lookahead)");
  benchCmd->add_option("--prefetch", bench.prefetch,
                       "pt's idle-time prefetch, a ray per N x N pixels (default " +
                           std::to_string(DEFAULT_PREFETCH) + ": off; see render --prefetch)");
  benchCmd->add_option("--far-prefetch", bench.farPrefetch, farPrefetchHelp());
  benchCmd->add_option("--budget-ms", bench.budgetMs,
                       "frame-time budget (see render --budget-ms; default off)");
  benchCmd->add_flag("--scale", bench.scale, "also dp frame time at 4 resolutions, first scene");
  benchCmd->add_option("--out", bench.out, "results JSON (default results.json)");
  benchCmd->add_option("--csv", bench.csv, "also a CSV file");
  benchCmd->add_option("--markdown", bench.markdown, "also a Markdown table in Table 1's shape");
  ServeFlags serve;
  CLI::App* serveCmd =
      app.add_subcommand("serve", "walk through a scene live in the browser (an HTTP viewer)");
  serveCmd->add_option("--scene", serve.scene, "the first scene: " + sceneNames());
  serveCmd->add_option("--scheduler", serve.scheduler, "sp, dp, pt (default) or graph");
  serveCmd->add_option("--backend", serve.backend, "cpu, cuda or auto");
  serveCmd->add_option("--width", serve.width,
                       "image width (default: 1500 on the GPU, 320 on the CPU)");
  serveCmd->add_option("--height", serve.height,
                       "image height (default: 1000 on the GPU, 200 on the CPU)");
  serveCmd->add_option("--budget-ms", serve.budgetMs, "frame-time budget, 0..1000 (default off)");
  serveCmd->add_option("--pool-bricks", serve.poolBricks, "brick pool slots");
  serveCmd->add_option("--path", serve.path,
                       "the camera: free (flown from the page, default) or a camera path (" +
                           movementNames() + ") followed until the page moves it");
  serveCmd->add_option("--port", serve.port, "TCP port (default 8080; 0: any free one)");
  serveCmd->add_option("--host", serve.host,
                       "address to listen on (default 127.0.0.1: this machine only; forward the "
                       "port with ssh -L to watch from another)");
  serveCmd->add_option("--quality", serve.quality, "JPEG quality, 1..100 (default 80)");
  CLI::App* scenesCmd = app.add_subcommand("scenes", "list the built-in scenes");
  CLI::App* infoCmd = app.add_subcommand("info", "build, devices and defaults");
  MeshCommands meshCommands(app);
  if (argc > 1 && argv[1][0] != '-') {
    std::string command = argv[1], names;
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
      known = known || sub->get_name() == command;
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    GVDP_INPUT_CHECK(known, "unknown command '", command, "' (commands: ", names, ")");
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    throw InputError(e.what());
  }
  if (renderCmd->parsed()) return runRender(render);
  if (timelineCmd->parsed())
    return runTimeline(timeline, timelineFrame, timelineAgain, timelinePng, timelineTrace,
                       timelineCostMap);
  if (benchCmd->parsed()) return runBenchCommand(bench);
  if (serveCmd->parsed()) return runServe(serve);
  if (scenesCmd->parsed()) return runScenes();
  if (infoCmd->parsed()) return runInfo();
  if (std::optional<int> status = meshCommands.runParsed()) return *status;
  return 2;
}

}  // namespace
}  // namespace gvdp::detail

int main(int argc, char** argv) {
  try {
    return gvdp::detail::run(argc, argv);
  } catch (const gvdp::InputError& e) {
    std::fprintf(stderr, "gvdp: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gvdp: internal error: %s\n", e.what());
    return 1;
  }
}
