// pt's idle-time prefetch (pt_body.h, at its top): on the device, the rays of the next frames
// as the camera's motion predicts them, marched as lookaheads (prefetchRay) while a frame's
// workers have nothing else to take (claimPrefetchItems); on the host, each frame's plan from
// what the last frame's prefetch did (prefetchPlanAfter, setPrefetch).
#pragma once

#include <algorithm>
#include <numeric>

#include "gvdp/cache/lookahead.h"
#include "gvdp/sched/pt/pt_tasks.h"

namespace gvdp::detail {

// Bricks a prefetch ray may enter (it claims at most MAX_LATE_CLAIMS of them). A prefetch task
// lasts as long as its longest ray, and a warp in one answers no production or relaunch: on an
// H100 (pt, --prefetch 4, 20 cells against --prefetch 0) 256 bricks gave +6.2% FPS (geometric
// mean) with perlin's forward and spinning walks 9-10% slower, 64 gave +6.5% with none more than
// 4% slower, 32 +5.5%; 4 claims a ray instead of 8, less in both.
constexpr uint32_t PT_PREFETCH_BRICKS = 64;

// Bricks a far prefetch's ray of a later pose may enter (its first pose's: PT_PREFETCH_BRICKS).
// At 1500 x 1000 a pose past a sphere's wall crosses more than 64 bricks of air before the next
// spheres: with 64, random-spheres' forward walk's far frames claimed nothing from their
// second on (H200, BENCHMARKS.md, session 60).
constexpr uint32_t PT_FAR_BRICKS = 256;

// How many levels above a brick that is not resident a prefetch ray's stand-in may be
// (cache/lookahead.h). A parent predicts where the ray becomes opaque; a coarser ancestor, all a
// region new in view has, is opaque far from where the ray at its own level meets the matter: a
// walk that turns or backs up brings such regions into view, the stand-in ended the prefetch
// ray there and the next frame's rays stopped on the bricks beyond it. H200, 25 pt cells, 1
// level against any: FPS x1.015 / x1.006 / x1.012, 1% lows x1.031 / x1.004 / x0.996 (2, 3 and 3
// rounds), the backward and sideways walks of perlin, fbm and forest +2-7% in every run, but
// aligned-spheres' walkthrough x0.93-0.94 in two of three (its spike frame 11 claims more bricks
// and takes 3.6-6.1 ms against 3.1-4.5); none at all: x1.013-1.014, aligned-spheres' walkthrough
// x0.94-0.96 in all three; 2 levels x1.007, 3 x1.009 (BENCHMARKS.md, session 55).
constexpr int PT_PREFETCH_STAND_IN_LEVELS = 1;

// Prefetch ray `item` (< prefetchItems): a predicted frame's ray (the next frame's: nearGrid's
// items first; a far prefetch's later poses: farGrid's each) through the centre of its grid's
// stride^2 pixels, marched from its start as a lookahead (cache/lookahead.h: stand-ins at most
// PT_PREFETCH_STAND_IN_LEVELS above, no waiting, no timestamp, nothing composited).
// Returns the bricks it entered, 0 for a later pose's (PT_PREFETCH_ENTERED counts the others).
template <class Pool>
GVDP_HD uint32_t prefetchRay(const PtContext& ctx, const Pool& pool, uint32_t item) {
  const PrefetchGrid* g = &ctx.nearGrid;
  uint32_t pose = 0;
  if (item >= g->items()) {
    item -= g->items();
    g = &ctx.farGrid;
    pose = 1 + item / g->items();
    item %= g->items();
  }
  FrameSetup f = ctx.prefetchFrame;
  f.eye = ctx.poses[pose].eye;
  f.basis = ctx.poses[pose].basis;
  uint32_t column = item % g->columns, row = item / g->columns;
  row = static_cast<uint32_t>(uint64_t{row} * g->rowStep % g->rows);
  const uint32_t s = g->stride;
  // A far prefetch's pixel in each s x s moves from frame to frame (idle frames march the same
  // ground again, one pose on).
  const uint32_t j = ctx.prefetchPoses > 1 ? static_cast<uint32_t>(f.frameIndex) * 7u + pose : 0u;
  int x = static_cast<int>(column * s + (s / 2 + j) % s);
  int y = static_cast<int>(row * s + (s / 2 + 3u * j) % s);
  Ray ray = f.primaryRay(x < f.width ? x : f.width - 1, y < f.height ? y : f.height - 1);
  const uint32_t entered = lookAhead<PoolReads::Coherent>(
      ray, f.lod, initialRayState(), ctx.cache, pool, StartAhead::prefetch(ctx),
      pose == 0 ? PT_PREFETCH_BRICKS : PT_FAR_BRICKS, PT_PREFETCH_STAND_IN_LEVELS);
  return pose == 0 ? entered : 0u;
}

// The first of the next PT_BATCH prefetch rays, prefetchItems when none is to be taken: none
// left, or no ray live. The prefetch fills the idle time of a frame's tail, that of a frame with
// no production too: it predicts the bricks of the next frame, which may have many. Only while a
// ray waited on a production (as written here until session 20, but read as the difference of
// PT_LIVE_WORK and PT_LIVE_RAYS, two loads apart while rays finished in between, that showed
// tasks in most tails without any): pt's floors x0.96, but aligned-spheres' walkthrough 417 ->
// 364 FPS, its 99th percentile 12 -> 20 ms (the prefetch in frames without production halved);
// ending the prefetch's marches with the frame's last ray: 381 FPS (H100, BENCHMARKS.md).
// A far prefetch (prefetchPoses > 1) holds the frame open (one unit of its live work, from its
// start: initialPtCounter) until its last rays are taken, its claims reach farClaims or a ray of
// the frame waited after all (a relaunch: the frame is not idle); from then on only the next
// frame's pose is marched, and only while rays are live.
GVDP_HD GVDP_INLINE void releaseFarHold(const PtContext& ctx) {
  if (atomicExch32(ctx.counter(PT_FAR_HOLD), 0u) != 0)
    atomicAdd32(ctx.counter(PT_LIVE_WORK), 0u - 1u);
}

GVDP_HD GVDP_INLINE uint32_t claimPrefetchItems(const PtContext& ctx) {
  const uint32_t items = ctx.prefetchItems;
  if (items == 0 || loadRelaxed32(ctx.counter(PT_NEXT_PREFETCH)) >= items) return items;
  bool far = loadRelaxed32(ctx.counter(PT_FAR_HOLD)) != 0;
  if (far && (loadRelaxed32(ctx.counter(PT_RELAUNCHED)) != 0 ||
              loadRelaxed32(ctx.counter(PT_PREFETCHES)) >= ctx.farClaims)) {
    releaseFarHold(ctx);
    far = false;
  }
  if (!far && loadRelaxed32(ctx.counter(PT_LIVE_RAYS)) == 0) return items;
  const uint32_t limit = far ? items : ctx.nearGrid.items();
  uint32_t first = atomicAdd32(ctx.counter(PT_NEXT_PREFETCH), static_cast<uint32_t>(PT_BATCH));
  if (far && first < items && first + PT_BATCH >= items) releaseFarHold(ctx);
  return first < limit ? first : items;
}

// After a production task's brick is published: a prefetch task's is stamped for the frame of its
// last pose (the next one, but for a far prefetch).
GVDP_HD GVDP_INLINE void markIfPrefetched(const PtContext& ctx, uint32_t id, const BrickKey& key) {
  if (id >= ctx.firstPrefetchId) markPrefetched(ctx.cache, key, ctx.prefetchPoses);
}

// What a frame's prefetch did, read from its counters `c` at its end: the prefetch rays it marched
// (of `items`) and the bricks they claimed, and whether it was idle: no ray of it waited.
// Also the next frame's rays marched (the first `nearItems`) and the bricks they entered.
struct PrefetchYield {
  uint32_t rays = 0, claims = 0;
  bool idle = false;
  uint32_t nearRays = 0, entered = 0;
};

inline PrefetchYield prefetchYield(const uint32_t* c, uint32_t items, uint32_t nearItems) {
  uint32_t taken = c[size_t{PT_NEXT_PREFETCH} * PT_COUNTER_STRIDE];  // claimed by batches: may pass
  taken = taken < items ? taken : items;
  return {taken, c[size_t{PT_PREFETCHES} * PT_COUNTER_STRIDE],
          c[size_t{PT_RELAUNCHED} * PT_COUNTER_STRIDE] == 0, taken < nearItems ? taken : nearItems,
          c[size_t{PT_PREFETCH_ENTERED} * PT_COUNTER_STRIDE]};
}

// The prefetch's density follows its yield: after a frame whose prefetch claimed less than a brick
// per PT_PREFETCH_YIELD rays (the next frame's bricks were resident: ground walked again, a camera
// that moves through what it has seen), a frame marches one ray per PT_PREFETCH_PROBE^2 of the
// prefetch's, a probe, until the probe claims at that yield again. A dense prefetch that finds
// nothing still marches its rays to their 64th brick in the frame's tail, beside the last rays:
// on random-spheres' walkthrough, whose floor frames' prefetch claimed 1-6 bricks for 94 000
// rays, the floor was 2.96-3.01 ms against 2.80-2.86 without a prefetch, 2.92-2.96 with the probe
// (H200, BENCHMARKS.md, session 25).
// After a frame without a prefetch (the first, a still camera), or one whose tail took none of its
// rays, the prefetch is dense; a frame whose tail marched few rays and claimed none makes the next
// one a probe. Either way the frame after a probe that claims, or a dense prefetch that finds
// nothing, corrects it: a swing of one frame.
constexpr uint32_t PT_PREFETCH_YIELD = 4096, PT_PREFETCH_PROBE = 4;

inline bool prefetchYielded(PrefetchYield last) {
  return uint64_t{last.claims} * PT_PREFETCH_YIELD >= last.rays;
}

inline uint32_t prefetchStrideAfter(uint32_t stride, PrefetchYield last) {
  if (stride == 0 || last.rays == 0) return stride;
  return prefetchYielded(last) ? stride : stride * PT_PREFETCH_PROBE;
}

// The far prefetch (`farPoses` > 1, --far-prefetch): after an idle frame (no ray waited) whose view
// is closed (PT_FAR_DEPTH: inside a sphere), the prefetch marches the next farPoses frames the
// motion predicts, the frame held open until their rays are taken (claimPrefetchItems) and their
// marches done (StartAhead::prefetch), its bricks stamped for the last pose; at most a claim per
// PT_FAR_DIV pixels. Its first pose, the next frame, is dense (`stride`): a brick of it missed
// makes a ray of the next frame wait, and that frame busy, which breaks the chain of far frames.
// The later poses are sparse, a ray per (stride * PT_FAR_SPARSE)^2 pixels, in a far frame after a
// busy one, and dense after a far frame that claimed at the yield. Their rays enter up to
// PT_FAR_BRICKS bricks and all go on after the frame's rays. Session 59's far prefetch (every
// pose sparse after a busy frame, 64 bricks a ray, marches that ended with the frame's rays once
// all were taken, after any idle frame): random-spheres' forward walk's exit frame 18.7-33.3 ms
// against 33.9-34.9 without, its 1% low 11-12% of its average (H200, BENCHMARKS.md, session 60).
// Session 57's dense start: floors x1.40, over-production 11.7%. PT_FAR_DIV balances the far
// frames against the exit frame: random-spheres forward's slowest frame 12.8 / 11.7 / 10.3 /
// 14.6 / 17.1 / 18.8 ms with 32 / 48 / 64 / 96 / 128 / 192 (the cap's far frames slower below
// 64, the exit frame above; H200, BENCHMARKS.md, session 62).
constexpr uint32_t PT_FAR_SPARSE = 8, PT_FAR_DIV = 64;

// The far prefetch starts only after a frame whose next-frame prefetch rays entered fewer than
// this many bricks each on average (PT_PREFETCH_ENTERED; or whose rays all ended before its
// prefetch took any, as on the CPU), and goes on while frames are idle (a far frame's next-frame
// rays pass the wall bricks it is producing: 25 a ray in random-spheres' forward walk): a view
// closed in front of the camera (inside a sphere about 1, random-spheres' open views 8-32 at 1500 x
// 1000), where the frame's own rays end early. An open view's frame (a floor frame, a walk frame
// with nothing to wait for) has its own rays' time to fill, and a far frame's marches made it
// later: far frames after any idle frame cost the floors x1.26, forest's 4.05 -> 7.35 ms; after one
// under 16 bricks a ray x1.105 (H200, 25 pt cells, BENCHMARKS.md, session 60).
constexpr uint32_t PT_FAR_DEPTH = 4;

struct PrefetchPlan {
  uint32_t stride = 0, poses = 1;
  uint32_t farStride = 0;  // the later poses' (a far prefetch)
};

inline PrefetchPlan prefetchPlanAfter(uint32_t stride, uint32_t farPoses, PrefetchYield last,
                                      uint32_t lastPoses) {
  const uint32_t next = prefetchStrideAfter(stride, last);
  const bool open = lastPoses == 1 && last.nearRays != 0 &&
                    uint64_t{last.entered} >= uint64_t{last.nearRays} * PT_FAR_DEPTH;
  if (stride == 0 || farPoses <= 1 || !last.idle || open) return {next, 1};
  const bool dense = lastPoses > 1 && last.rays != 0 && prefetchYielded(last);
  return {stride, farPoses, dense ? stride : stride * PT_FAR_SPARSE};
}

inline PrefetchGrid prefetchGrid(const FrameSetup& f, uint32_t stride) {
  PrefetchGrid g;
  if (stride == 0) return g;
  g.stride = stride;
  g.columns = (static_cast<uint32_t>(f.width) + stride - 1) / stride;
  g.rows = (static_cast<uint32_t>(f.height) + stride - 1) / stride;
  uint32_t step = static_cast<uint32_t>(0.618 * g.rows) | 1u;
  while (std::gcd(step, g.rows) != 1) step += 2;
  g.rowStep = step % g.rows;
  return g;
}

// A frame's prefetch (none: stride 0, a tile, a cold cache, no frame just before it, or one from
// the same view): rays of the next frame as the motion from `previous` predicts it (and of the
// frames after it: a far prefetch's poses), one per stride x stride pixels, the rows taken in an
// order that spreads a partial prefetch over the screen (a step about 0.618 of the rows, prime
// to them).
inline void setPrefetch(PtContext& ctx, const FrameSetup& f, const FrameSetup* previous,
                        PrefetchPlan plan) {
  ctx.prefetchItems = 0;
  ctx.prefetchPoses = 1;
  const uint32_t stride = plan.stride;
  if (stride == 0 || previous == nullptr || f.coldCache || f.width != f.imageWidth ||
      f.height != f.imageHeight || previous->frameIndex + 1 != f.frameIndex ||
      previous->width != f.width || previous->height != f.height || sameView(*previous, f))
    return;  // a still camera: the next frame needs the bricks this frame's rays leave resident
  ctx.prefetchFrame = predictNextFrame(*previous, f);
  ctx.nearGrid = prefetchGrid(f, stride);
  ctx.farGrid = prefetchGrid(f, plan.farStride);
  // The poses: the same step and turn again and again (predictNextFrame).
  const uint32_t poses = std::min(plan.poses, PT_FAR_MAX_POSES);
  FrameSetup before = f, pose = ctx.prefetchFrame;
  for (uint32_t k = 0; k < poses; ++k) {
    ctx.poses[k] = {pose.eye, pose.basis};
    FrameSetup after = predictNextFrame(before, pose);
    before = pose;
    pose = after;
  }
  ctx.prefetchPoses = poses;
  ctx.prefetchItems = ctx.nearGrid.items() + ctx.farGrid.items() * (poses - 1);
  ctx.farClaims = static_cast<uint32_t>(f.pixelCount()) / PT_FAR_DIV;
}

}  // namespace gvdp::detail
