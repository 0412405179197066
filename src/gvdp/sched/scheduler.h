// One interface for every scheduler (docs/DESIGN.md "Schedulers"): render one frame of a sequence
// into an RGBA8 image and report what it did. All schedulers render the same image on a backend
// for the same frame sequence; `direct` (no cache) is the reference.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "gvdp/base/gpu.h"
#include "gvdp/base/image.h"
#include "gvdp/cache/cache_host.h"
#include "gvdp/profile/frame_clock.h"
#include "gvdp/profile/frame_timeline.h"
#include "gvdp/render/frame.h"
#include "gvdp/sched/producer_kernels.h"

namespace gvdp::detail {

struct ImportanceMap;      // importance_map.h
struct ImportanceOptions;  // importance_map.h

enum class Backend { Cpu, Cuda };
enum class SchedulerKind { Direct, Sp, Dp, Pt, Graph };

std::string_view backendName(Backend b);
Backend parseBackend(std::string_view name);  // "cpu" | "cuda"; throws InputError
std::string_view schedulerName(SchedulerKind k);
SchedulerKind parseScheduler(std::string_view name);  // throws InputError

struct FrameStats {
  int index = 0;
  double ms = 0.0;  // GPU: CUDA events around the frame's work; CPU: wall clock
  int64_t unfinishedPixels = 0;
  int passes = 0;                // render passes (sp iterations)
  bool degraded = false;         // some bricks could not be produced: coarser levels stood in
  uint64_t launches = 0;         // dp: device-side launches; pt: tasks run (render + production)
  uint64_t launchFailures = 0;   // dp: launches refused (pending-launch buffer full); pt: no id
  uint64_t deferred = 0;         // dp: productions left to the sweep (launch depth limit)
  int64_t sweptPixels = 0;       // dp: rays the device-side schedule left to the sp sweep
  uint64_t relaunchedRays = 0;   // pt: parked rays a production queued again
  uint64_t longestWaitList = 0;  // pt: the most rays one production queued again
  bool spike = false;            // pt: its backlog outgrew the producer SMs (pt_worker.cuh)
  uint64_t lookaheadClaims = 0;  // pt: bricks claimed ahead of stopped rays (cache/lookahead.h)
  uint64_t prefetchClaims = 0;   // pt: bricks claimed for the next frame (idle-time prefetch)
  uint64_t prefetchRays = 0;     // pt: the prefetch's rays marched, of prefetchItems offered
  uint64_t prefetchEntered = 0;  // pt: the bricks its rays of the next frame entered
  uint64_t prefetchItems = 0;
  int tiles = 1;        // tiles the image was rendered as (tiles/tiled_frame.h)
  int tileSplits = 0;   // renders replaced by tiles (the pool overflowed)
  int tilePlans = 0;    // importance pre-passes run to plan tiles (tiles/tile_plan.h)
  double planMs = 0.0;  // their time (pre-pass and subdivision; included in ms)
  int lodBias = 0;      // a degraded frame's coarser LOD (tiles/tiled_frame.h)
  CacheStats cache;
  TimelineCapture timeline;  // when SchedulerOptions::timeline
  RayCosts rayCosts;         // when SchedulerOptions::rayCosts (cached schedulers)
};

// pt's lookahead (cache/lookahead.h): bricks a stopped ray claims beyond the one it waits for.
// 2 by default: on an H100, once pt's march was inlined once (BENCHMARKS.md, session 13), the 25
// cells gave FPS x1.048 / x1.059 / x1.066 and 1% lows x1.117 / x1.128 / x1.144 for 2 / 3 / 4
// bricks against none (forest walkthrough +19%, aligned-spheres +22%; the spinning walks of
// perlin and fbm 9-17% slower), with over-production up to 8.8% / 10.2% / 11.8% of the bricks
// produced: 2 keeps it under the 10% the issue allows. Before, 4 had made perlin 4-14% slower.
constexpr uint32_t DEFAULT_LOOKAHEAD = 2;
constexpr uint32_t MAX_LOOKAHEAD = 64;
// pt's lookahead in a frame's tail (ptTailLookahead). 24 since session 76: with the tail's rule
// that only a parked ray looks ahead (pt_body.h: lookaheadPlan), H200, 25 pt cells against 16, two
// calls (3 and 4 rounds): FPS x1.001 / x1.002, 1% lows x1.011 / x1.012, random-spheres'
// walkthrough frame 12 4.86-4.87 -> 4.76-4.77 ms and its idle 9.1-9.2% -> 6.0-7.1%, perlin's
// 1.81-1.85 -> 1.82-1.83 ms, over-production at most 5.7% -> 7.6-8.0%; 32: FPS x0.996 / x1.003,
// 1% lows x1.012 / x1.012, frame 12 4.66-4.67 ms, idle 5.5-5.9%, over-production 8.9-9.1%, too
// near the 10% issue 14 allows (BENCHMARKS.md session 76).
constexpr uint32_t DEFAULT_TAIL_LOOKAHEAD = 24;
// A frame's tail: at most one ray in PT_TAIL_SHARE live (pt_body.h: lookaheadPlan). 16 since
// session 73 (H200, 25 pt cells, one binary against 256, 2 + 3 rounds): FPS x1.010 / x1.007,
// 1% lows x1.035 / x1.022 (aligned-spheres' walkthrough 609-615 -> 639-663 FPS, its spinning walk
// 290-296 -> 311), over-production at most 4.1-4.2% -> 5.8%, a cold cache's first frame 153 ->
// 160 ms; 8: x1.010, x1.024, 6.3%, 168 ms; 32: x1.003, x1.021; 64: x1.005, x1.028. The tail's
// rule was one in 256 since session 23, when it also raised the lookahead to 8 (an H100).
constexpr uint32_t PT_TAIL_SHARE = 16;

// pt's idle-time prefetch (pt_prefetch.h): a ray of the predicted next frame per N x N pixels, 0:
// off. Off by default since session 68: on an H100 (BENCHMARKS.md, "Idle-time prefetch") 4 had made
// pt's 25 cells faster on the whole and 2 was no better, but since EMPTY boxes mark their members
// and an EMPTY brick's rays go on before its box is grown (sessions 53, 67) the frame's own rays
// find the bricks at least as fast, and the prefetch's marches and productions after the frame's
// last ray are most of a terrain frame's end: perlin's walkthrough frame 12 2.22 -> 1.84 ms
// without it. H200, 25 pt cells, two calls of 3 rounds, --prefetch 0 against 4: FPS x1.045 and
// x1.042, 1% lows x0.999 and x0.996, perlin's and fbm's backward and sideways walks +5-19%; it
// loses random-spheres spinning (-6%) and aligned-spheres' walkthrough (-8% in one call, 0 in
// the other). A far prefetch (--far-prefetch) needs it: FAR_PREFETCH_STRIDE unless --prefetch says.
constexpr uint32_t DEFAULT_PREFETCH = 0;
constexpr uint32_t FAR_PREFETCH_STRIDE = 4;
constexpr uint32_t MAX_PREFETCH = 64;

// pt's far prefetch (pt_prefetch.h: prefetchPlanAfter): after an idle frame whose view is closed
// (inside a sphere, a tree, a hill), the prefetch marches the next N frames the camera's motion
// predicts, so that the frame where the view opens finds most of its bricks (random-spheres'
// forward walk: its exit frame 34 -> 10 ms, the cell's 1% low 11% -> 42% of its average; H200,
// BENCHMARKS.md, sessions 60-62). 0 (or 1: the next frame only): off, the default, since the far
// frames cost the cells they help some FPS (those two walks x0.85 and x0.65; 25 pt cells FPS
// x0.978, 1% lows x1.066).
constexpr uint32_t MAX_FAR_PREFETCH = 16;

// A frame-time budget (BrickCache::setBudget): NO_BUDGET (exact frames) by default.
constexpr double NO_BUDGET = -1.0;
constexpr double MAX_BUDGET_MS = 60000.0;

struct SchedulerOptions {
  Backend backend = Backend::Cpu;
  SchedulerKind kind = SchedulerKind::Sp;
  uint32_t poolBricks = 0;       // 0: the backend's default
  uint32_t pendingLaunches = 0;  // dp: CDP pending-launch buffer (tasks on the CPU); 0: default
  bool timeline = false;         // record the GPU-cores timeline of every frame (profile/)
  bool rayCosts = false;         // record each pixel's lookups, samples, stops (cached ones)
  uint32_t lookahead = DEFAULT_LOOKAHEAD;           // pt: missing bricks a stopped ray claims ahead
  uint32_t tailLookahead = DEFAULT_TAIL_LOOKAHEAD;  // pt: at least this many in a frame's tail
  uint32_t prefetch = DEFAULT_PREFETCH;             // pt: a prefetch ray per N x N pixels (0: none)
  uint32_t farPrefetch = 0;     // pt: predicted frames a far prefetch marches (0: off; it turns
                                // the prefetch on: prefetchOf; see above)
  double budgetMs = NO_BUDGET;  // cached schedulers: past it, rays show coarser levels; < 0: none
};

// pt's lookahead in a frame's tail (at most one ray in PT_TAIL_SHARE live: pt_body.h,
// lookaheadPlan, which there also passes the bricks not resident): at least `tailLookahead` bricks,
// unless the lookahead is off. There the last chains of productions are what is left of the frame.
// On an H100 (25 pt cells, BENCHMARKS.md, session 23), 8 bricks once one ray in 256 is live gave
// FPS x1.046, random-spheres' walkthrough frame-12 idle 12% -> 6-8%, over-production at most 9.4%
// (fbm spinning, 8.1% without); once one ray in 32 is live (session 14's tail), fbm spinning
// over-produced 11.5-16.6%, over the 10% issue 14 allows; 4 to 6 bricks at one ray in 32 to 256
// gave less (FPS x1.025-1.043). 16 by default since session 41 (H200, 25 pt cells against 8, 2 + 4
// rounds): 1% lows x1.014 / x1.017, FPS x1.004 / x1.003, random-spheres' frame-12 idle 6.2-7.9% ->
// 3.5-5.9%, fbm spinning's over-production 5.4-5.8% -> 8.1-8.3%; 32 over-produced 12.6% there.
// Re-swept with the prefetch off (session 69, 3 + 5 rounds): 8 and 32 made random-spheres' frame
// 12 4-5% longer (5.03-5.09 -> 5.28 ms), 64 FPS x0.975 at 10.0% over-production; --lookahead 4
// x1.003-1.004, within the spread. Those sweeps ran with the tail at one ray in 256 live; it
// begins at one in 16 since session 73 (PT_TAIL_SHARE above), where 8 bricks gave FPS
// x0.988 and 32 x0.995 at 9.9% over-production (2 rounds).
inline uint32_t ptTailLookahead(const SchedulerOptions& o) {
  return o.lookahead == 0 || o.lookahead > o.tailLookahead ? o.lookahead : o.tailLookahead;
}

// The budget in nanoseconds for BrickCache::setBudget (negative: none).
inline int64_t budgetNsOf(const SchedulerOptions& o) {
  return o.budgetMs < 0.0 ? -1 : static_cast<int64_t>(o.budgetMs * 1e6 + 0.5);
}

// Default pool sizes: about 2 GB on the GPU (the paper), 128 MB on the CPU.
constexpr uint32_t DEFAULT_POOL_BRICKS_CUDA = 500000;
constexpr uint32_t DEFAULT_POOL_BRICKS_CPU = 32768;
constexpr uint32_t DEFAULT_PENDING_LAUNCHES = 1u << 16;

// The pool a scheduler with these options holds (its backend's default for 0).
inline uint32_t poolBricksOf(const SchedulerOptions& o) {
  if (o.poolBricks) return o.poolBricks;
  return o.backend == Backend::Cuda ? DEFAULT_POOL_BRICKS_CUDA : DEFAULT_POOL_BRICKS_CPU;
}

// A scheduler renders the frames of a sequence. render() keeps the books of every frame (index,
// clock, timeline) around the scheduler's own steps: prepareFrame (before the clock: allocations
// that follow the frame size), renderFrame (timed and recorded: the frame's work, up to the
// resolved image on the backend), finishFrame (after the clock: the image to the host, counters).
// dp's pending-launch buffer (the default for 0).
inline uint32_t pendingLaunchesOf(const SchedulerOptions& o) {
  return o.pendingLaunches ? o.pendingLaunches : DEFAULT_PENDING_LAUNCHES;
}

// pt's prefetch as used: a far prefetch (more than one predicted frame) extends the idle-time
// prefetch, so with the prefetch off (the default) it turns it on at FAR_PREFETCH_STRIDE.
inline uint32_t prefetchOf(uint32_t prefetch, uint32_t farPrefetch) {
  return prefetch == 0 && farPrefetch > 1 ? FAR_PREFETCH_STRIDE : prefetch;
}

// The options with every default made explicit, as the scheduler will use them: the backend's
// pool (0 for direct, which has none) and dp's pending launches (0 for the others). Resolved
// once, at the top (the command line, the benchmark), and reported as used (stats.json).
inline SchedulerOptions resolvedOptions(SchedulerOptions o) {
  o.poolBricks = o.kind == SchedulerKind::Direct ? 0 : poolBricksOf(o);
  o.pendingLaunches = o.kind == SchedulerKind::Dp ? pendingLaunchesOf(o) : 0;
  o.lookahead = o.kind == SchedulerKind::Pt ? o.lookahead : 0;
  o.tailLookahead = o.kind == SchedulerKind::Pt ? o.tailLookahead : 0;
  o.prefetch = o.kind == SchedulerKind::Pt ? prefetchOf(o.prefetch, o.farPrefetch) : 0;
  o.farPrefetch = o.kind == SchedulerKind::Pt && o.prefetch != 0 ? o.farPrefetch : 0;
  o.budgetMs = o.kind == SchedulerKind::Direct ? NO_BUDGET : o.budgetMs;
  return o;
}

class Scheduler {
 public:
  Scheduler(Backend backend, ProducerKernelsPtr producer);
  virtual ~Scheduler();
  // Records the timeline of the following frames into FrameStats::timeline.
  void recordTimeline(std::unique_ptr<FrameTimeline> t) { timeline_ = std::move(t); }
  // Records each pixel's brick lookups, samples and stops of the following frames into
  // FrameStats::rayCosts (cached schedulers).
  void recordRayCosts(bool on) { rayCosts_ = on; }
  // Renders `frame` into `out` (resized to the frame). Frames of a sequence come in order.
  FrameStats render(const FrameSetup& frame, Image& out) { return render(frame, &out); }
  // With `out` null the image stays on the device, at deviceImage() (cuda backend only).
  FrameStats render(const FrameSetup& frame, Image* out);
  // The last frame's RGBA8 pixels in device memory (CUDA schedulers), else null.
  virtual const uint32_t* deviceImage() const { return nullptr; }
  // The stream all of the scheduler's GPU work runs on (cuda backend), else null.
  GpuStream stream() const { return stream_.get(); }
  // Bytes of every structure the scheduler holds (after the last frame).
  virtual MemoryReport memory() const = 0;
  // The importance pre-pass of tiled frames (importance_map.h) for `frame`, on this backend.
  ImportanceMap importance(const FrameSetup& frame, const ImportanceOptions& options) const;

 protected:
  virtual void prepareFrame(const FrameSetup&) {}
  virtual void renderFrame(const FrameSetup& frame, Image& out, FrameStats& stats) = 0;
  virtual void finishFrame(const FrameSetup&, Image&, FrameStats&) {}
  bool hostImageWanted() const { return hostImage_; }
  const ProducerKernels& producer() const { return *producer_; }
  const CudaProducerKernels& cudaProducer() const { return *producer_->cuda(); }

 private:
  ProducerKernelsPtr producer_;
  Backend backend_;
  OwnedGpuStream stream_;
  bool hostImage_ = true;
  std::unique_ptr<FrameClock> clock_;
  std::unique_ptr<FrameTimeline> timeline_;
  bool rayCosts_ = false;
};

// What every cached scheduler reports of its cache after a frame.
template <class Cache>
void addCacheStats(Cache& cache, FrameStats& stats) {
  stats.cache = cache.frameStats();
  stats.degraded = stats.degraded || cache.degraded();
  stats.rayCosts = cache.rayCosts();
}

// Throws InputError when the backend is not available (no CUDA build or no device).
void requireBackend(Backend backend);
// Starts (on) or stops recording the timeline of the scheduler's frames, on its backend's clock.
void recordTimelineOf(Scheduler& s, Backend backend, bool on);
// The scheduler of `options` over a producer's kernels (for the cuda backend, compiled by nvcc).
std::unique_ptr<Scheduler> makeScheduler(const SchedulerOptions& options,
                                         ProducerKernelsPtr producer);

}  // namespace gvdp::detail
