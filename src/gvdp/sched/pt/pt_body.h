// The persistent-threads scheduler (pt) as one protocol for both backends: workers (GPU warps,
// CPU threads) pull tasks from device work queues until every ray of the frame has finished and
// every production task started in it has run.
//
// Queues (lock-free rings of uint32, one atomic per batch):
//   tasks    production task ids, served first;
//   rays     pixels of relaunched rays, taken 32 at a time (full warps, seed 004);
//   fresh    the screen itself, 8x4-pixel halves of the 8x8 tiles, through a counter.
// A ray that finds a brick MISSING takes a task id from the `freeIds` ring and claims the brick
// with a CAS from MISSING to the task's name (ENTRY_PRODUCTION_TASK + id); the winner queues
// the task, a loser gives the id back. A ray that stops on a brick in
// production parks itself on that task's wait list (a lock-free stack through `waitNext`);
// the production closes the list after publishing the brick and queues its rays as full warps.
// A push onto a closed list fails and the ray marches on: no ray is ever lost or held twice.
//
// A stopped ray then looks ahead (cache/lookahead.h): it claims up to `lookahead` more missing
// bricks on its path, each with an id from a ring of its own (`lookaheadIds`), taken only when
// one is ready (never waited for): without an id the brick stays MISSING for a ray to claim.
//
// Idle-time prefetch (`prefetch`, DEFAULT_PREFETCH; 0: off): a worker with nothing to take and no
// production to help, while rays of the frame are live (its tail; claimPrefetchItems), unless the
// camera stands still (setPrefetch), marches rays of the next frame as the camera's motion predicts
// it (predictNextFrame), one per prefetch x prefetch pixels (a sixteenth of those after a frame
// whose prefetch found next to nothing: prefetchStrideAfter), as lookaheads from their start
// (stand-ins a level above at most, no waiting, at most MAX_LATE_CLAIMS claims a ray), with ids
// from a third ring (`prefetchIds`), and only while half the frame's free slots are left (the
// lookahead's claims too): the frame's own productions never fail for them. A prefetched brick is
// stamped for the next frame (markPrefetched), whose end counts whether a ray used it. Nothing is
// composited. A far prefetch (GVDP_PT_FAR, off by default: prefetchPlanAfter) marches several
// predicted frames after an idle one with a closed view.
//
// Capacities, not guesses: a ray is in at most one place (running, in `rays`, or on one list),
// so `rays` holds at most `pixels` items; every unfinished task from `freeIds` has its winning
// ray parked on it or about to be, so at most pixels + workers of those ids are out at once, and
// a ray that needs one always gets one (it waits only for a task in flight to finish). Claims
// no ray waits for (the lookahead's, and those past a budgeted frame's deadline) take ids from a
// separate ring of PT_LOOKAHEAD_IDS, only when one is ready. `tasks` holds at most all ids.
#pragma once

#include <numeric>

#include "gvdp/cache/lookahead.h"
#include "gvdp/sched/pt/pt.h"
#include "gvdp/sched/ray_tasks.h"
#include "gvdp/sched/tile_order.h"

namespace gvdp::detail {

constexpr uint32_t LIST_END = 0xffffffffu, LIST_CLOSED = 0xfffffffeu;
constexpr int PT_BATCH = 32;                     // rays per render task (a warp)
constexpr int PT_COUNTER_STRIDE = 32;            // counters sit 128 bytes apart (no false sharing)
constexpr uint32_t PT_LOOKAHEAD_IDS = 1u << 15;  // task ids for the lookahead's claims
constexpr uint32_t PT_PREFETCH_IDS = 1u << 14;   // task ids for the prefetch's claims
// A frame's tail: at most one ray in PT_TAIL_SHARE live (PtContext::tailLookahead).
constexpr uint32_t PT_TAIL_SHARE = 256;

enum PtCounter : int {
  PT_RAY_HEAD,
  PT_RAY_TAIL,
  PT_RAY_READY,
  PT_TASK_HEAD,
  PT_TASK_TAIL,
  PT_TASK_READY,
  PT_FREE_HEAD,
  PT_FREE_TAIL,
  PT_FREE_READY,
  PT_LOOK_HEAD,  // the lookahead's free ids
  PT_LOOK_TAIL,
  PT_LOOK_READY,
  PT_PREFETCH_HEAD,  // the prefetch's free ids
  PT_PREFETCH_TAIL,
  PT_PREFETCH_READY,
  PT_NEXT_ITEM,         // next item of the screen (fresh rays; tile_order.h)
  PT_LIVE_WORK,         // rays and production tasks not finished; the frame is over at 0
  PT_PRODUCTIONS,       // production tasks run
  PT_RELAUNCHED,        // rays queued again by a production
  PT_RENDER_TASKS,      // render tasks run (fresh and relaunched)
  PT_LOOKAHEAD,         // bricks claimed by lookaheads
  PT_LIVE_RAYS,         // rays not finished (the prefetch runs only while some are)
  PT_NEXT_PREFETCH,     // next prefetch ray
  PT_PREFETCHES,        // bricks claimed by the prefetch
  PT_OPEN,              // productions with chunks left for helpers (pt_worker.cuh: openProduction)
  PT_EXITED,            // warps that left the loop (counted with producer SMs only: pt_worker.cuh)
  PT_IN_FLIGHT,         // production tasks taken and not ended (the same)
  PT_SPIKE,             // nonzero once the frame's backlog reached spikeBacklog (the same)
  PT_LONGEST_LIST,      // the most rays one production queued again (a wait list's length)
  PT_FAR_HOLD,          // 1 while a far prefetch holds the frame open (claimPrefetchItems)
  PT_PREFETCH_ENTERED,  // bricks the next frame's prefetch rays entered (prefetchRay)
  PT_COUNTER_COUNT
};

static_assert(PT_RAY_HEAD == 0 && PT_FREE_HEAD == 6 && PT_LOOK_HEAD == 9 && PT_NEXT_ITEM == 15,
              "the five rings' three counters come first, in ptRingFilled's order");

// A bounded multi-producer multi-consumer ring (D. Vyukov's): a slot is (sequence, value) in one
// 64-bit word; the producer of position p waits for sequence p and leaves p + 1, the consumer
// waits for p + 1 and leaves p + capacity, so each slot serves its laps strictly in order.
// Positions only grow within a frame (32 bits, wrapping harmlessly: capacity divides 2^32).
// Claims take items off `ready` with a single CAS and no retry loop: thousands of warps polling
// a queue with CAS loops on its head spent their time retrying (perlin frame: 133 ms, against
// 39 ms with one attempt per poll, H100).
struct Ring {
  uint64_t* slots;
  uint32_t mask;    // capacity - 1, capacity a power of two
  uint32_t* head;   // next position to claim
  uint32_t* tail;   // next position to reserve
  uint32_t* ready;  // items published and not claimed
};

GVDP_HD GVDP_INLINE uint64_t ringSlot(uint32_t sequence, uint32_t value) {
  return static_cast<uint64_t>(sequence) << 32 | value;
}

// Slot i of a ring whose first `filled` positions hold the values 0, 1, ... (free ids).
GVDP_HD GVDP_INLINE uint64_t ringInitialSlot(uint32_t i, uint32_t filled) {
  return i < filled ? ringSlot(i + 1, i) : ringSlot(i, 0);
}

GVDP_HD GVDP_INLINE uint32_t ringReserve(const Ring& r, uint32_t n) {
  return atomicAdd32(r.tail, n);
}

GVDP_HD GVDP_INLINE void ringStore(const Ring& r, uint32_t position, uint32_t value) {
  uint64_t* s = &r.slots[position & r.mask];
  while (static_cast<uint32_t>(loadAcquire64(s) >> 32) != position) spinPause();  // last lap
  storeRelease64(s, ringSlot(position + 1, value));
}

// Makes n stored items claimable.
GVDP_HD GVDP_INLINE void ringPublish(const Ring& r, uint32_t n) {
  atomicAdd32(r.ready, n);
}

GVDP_HD GVDP_INLINE void ringPush(const Ring& r, uint32_t value) {
  ringStore(r, ringReserve(r, 1), value);
  ringPublish(r, 1);
}

// Claims up to n published items: returns how many, the first position in *position. One CAS
// attempt, no retry loop: a worker that loses the race looks for other work and comes back.
GVDP_HD GVDP_INLINE uint32_t ringClaim(const Ring& r, uint32_t n, uint32_t* position) {
  uint32_t ready = loadRelaxed32(r.ready);
  if (ready == 0) return 0;
  uint32_t k = ready < n ? ready : n;
  if (atomicCas32(r.ready, ready, ready - k) != ready) return 0;
  *position = atomicAdd32(r.head, k);
  return k;
}

// The value at a claimed position (waiting for its producer's store); frees the slot.
GVDP_HD GVDP_INLINE uint32_t ringTake(const Ring& r, uint32_t position) {
  uint64_t* s = &r.slots[position & r.mask];
  uint64_t v;
  while (static_cast<uint32_t>((v = loadAcquire64(s)) >> 32) != position + 1) spinPause();
  storeRelease64(s, ringSlot(position + r.mask + 1, 0));
  return static_cast<uint32_t>(v);
}

// Warps per block of the GPU's persistent kernel (pt_worker.cuh: PT_BLOCK / 32).
constexpr uint32_t PT_WORKER_WARPS = 8;

// Productions in flight that any idle warp of the grid may help compute (the GPU's workers,
// pt_worker.cuh; null on the CPU): per worker warp `w` (block * PT_WORKER_WARPS + warp), its
// brick's key, staged samples and chunk counters, and bit w of `open` while it has chunks to claim.
struct PtProductions {
  Rgba8* stage;        // BRICK_SAMPLE_COUNT per worker warp
  BrickKey* key;       // per worker warp
  uint32_t* next;      // next chunk to claim (runs past the chunk count)
  uint32_t* done;      // chunks computed
  uint32_t* nonEmpty;  // nonzero once a chunk found a non-empty sample
  uint32_t* open;      // a bit per worker warp
  uint32_t openWords;
  uint32_t* openCount;  // the bits set (ctx.counter(PT_OPEN)), read before a search
};

// A prefetch's rays over one pose: one per stride x stride pixels, `columns` of them a row, the
// rows taken in the order k * rowStep mod rows (setPrefetch).
struct PrefetchGrid {
  uint32_t stride = 1, columns = 1, rows = 1, rowStep = 0;
  GVDP_HD uint32_t items() const { return columns * rows; }
};

// A predicted frame's camera (a far prefetch's poses: setPrefetch).
struct PrefetchPose {
  Vec3f eye;
  CameraBasis basis;
};

struct PtContext {
  FrameSetup frame;
  CacheView cache;
  RayState* payload;
  Ring rays, tasks, freeIds;
  Ring lookaheadIds;               // values v: task id firstLookaheadId + v
  uint32_t firstLookaheadId;       // ids below come from freeIds
  uint32_t lookahead;              // bricks a stopped ray claims ahead of it (0: none)
  uint32_t tailRays;               // live rays at most: the frame's tail
  uint32_t tailLookahead;          // its lookahead (sched/scheduler.h: ptTailLookahead)
  Ring prefetchIds;                // values v: task id firstPrefetchId + v
  uint32_t firstPrefetchId;        // ids from here on are the prefetch's
  FrameSetup prefetchFrame;        // the predicted next frame (setPrefetch)
  PrefetchGrid nearGrid, farGrid;  // the next frame's rays, each later pose's
  uint32_t prefetchItems;          // prefetch rays in all (0: no prefetch)
  BrickKey* taskKey;               // per task id
  uint32_t* waitHead;              // per task id: LIST_END, a pixel, or LIST_CLOSED
  uint32_t* waitNext;              // per pixel
  uint32_t* counters;              // PtCounter, PT_COUNTER_STRIDE apart
  uint32_t itemCount;              // items of the screen (tile_order.h: orderedItemCount)
  TileOrder tiles;                 // their order (the GPU's; row-major on the CPU)
  PtProductions productions;       // the GPU's (pt_worker.cuh)
  uint32_t producerShare;          // the GPU's producer SMs (pt_worker.cuh: roleNow); 0: none
  uint32_t spikeBacklog;           // the backlog from which a frame has no producer SMs (the same)
  // The prefetch's predicted frames (a far prefetch: more than one), their cameras (the next
  // frame's first, nearGrid's rays; the others farGrid's each), and a far prefetch's claims at
  // most.
  uint32_t prefetchPoses = 1;
  PrefetchPose poses[PT_FAR_MAX_POSES];
  uint32_t farClaims = 0;

  GVDP_HD uint32_t* counter(PtCounter c) const { return &counters[c * PT_COUNTER_STRIDE]; }
};

// A key another warp or thread may have written (a task's, or a block's production's).
GVDP_HD GVDP_INLINE BrickKey loadBrickKey(const BrickKey* key) {
  const uint32_t* k = reinterpret_cast<const uint32_t*>(key);
  return {{static_cast<int>(loadRelaxed32(k)), static_cast<int>(loadRelaxed32(k + 1)),
           static_cast<int>(loadRelaxed32(k + 2))},
          static_cast<int>(loadRelaxed32(k + 3))};
}

GVDP_HD GVDP_INLINE BrickKey loadTaskKey(const PtContext& ctx, uint32_t id) {
  return loadBrickKey(&ctx.taskKey[id]);
}

// Closes a task's wait list (after its brick is published) and returns its first ray: walk the
// rest through waitNext, reading a link before queueing its ray, which may park again.
GVDP_HD GVDP_INLINE uint32_t closeWaitList(const PtContext& ctx, uint32_t id) {
  uint32_t first = atomicExch32(&ctx.waitHead[id], LIST_CLOSED);
  fenceSeqCst();
  return first;
}

// Queues the rays of a closed wait list again, one by one; returns how many.
GVDP_HD GVDP_INLINE uint32_t requeueRays(const PtContext& ctx, uint32_t first) {
  uint32_t n = 0;
  for (uint32_t p = first; p != LIST_END; ++n) {
    uint32_t next = loadRelaxed32(&ctx.waitNext[p]);
    ringPush(ctx.rays, p);
    p = next;
  }
  return n;
}

// A task id back to the ring it came from.
GVDP_HD GVDP_INLINE void releaseTaskId(const PtContext& ctx, uint32_t id) {
  if (id < ctx.firstLookaheadId)
    ringPush(ctx.freeIds, id);
  else if (id < ctx.firstPrefetchId)
    ringPush(ctx.lookaheadIds, id - ctx.firstLookaheadId);
  else
    ringPush(ctx.prefetchIds, id - ctx.firstPrefetchId);
}

// Claims a MISSING brick for task `id`: a CAS straight from MISSING to the task's name, so that a
// ray stopping on it never waits for the winner (a spin on a lane of its own warp); the winner
// queues the task, a loser gives its id back. True for the winner.
GVDP_HD GVDP_INLINE bool startTask(const PtContext& ctx, uint32_t id, int level, Vec3i g,
                                   uint32_t* entry) {
  uint32_t* k = reinterpret_cast<uint32_t*>(&ctx.taskKey[id]);
  storeRelaxed32(k, static_cast<uint32_t>(g.x));
  storeRelaxed32(k + 1, static_cast<uint32_t>(g.y));
  storeRelaxed32(k + 2, static_cast<uint32_t>(g.z));
  storeRelaxed32(k + 3, static_cast<uint32_t>(level));
  storeRelaxed32(&ctx.waitHead[id], LIST_END);
  fenceSeqCst();  // the key and the list before the name
  if (atomicCas32(entry, ENTRY_MISSING, ENTRY_PRODUCTION_TASK + id) == ENTRY_MISSING) {
    atomicAdd32(ctx.counter(PT_LIVE_WORK), 1u);  // the frame ends after the task (endTask)
    ringPush(ctx.tasks, id);
    return true;
  }
  // Lost: close the list again (a ray with a stale name of this id may be on it).
  requeueRays(ctx, closeWaitList(ctx, id));
  releaseTaskId(ctx, id);
  return false;
}

// A claim no ray waits for (a lookahead's, one past the frame's deadline, or the prefetch's): an
// id from `ids` (values v: task id first + v) if one is ready (one attempt), then startTask;
// without one the brick stays MISSING. True when this claim started the task.
GVDP_HD GVDP_INLINE bool startTaskFrom(const PtContext& ctx, const Ring& ids, uint32_t first,
                                       int level, Vec3i g, uint32_t* entry) {
  uint32_t position = 0;
  if (ringClaim(ids, 1, &position) == 0) return false;
  return startTask(ctx, first + ringTake(ids, position), level, g, entry);
}

GVDP_HD GVDP_INLINE bool startTaskAhead(const PtContext& ctx, int level, Vec3i g, uint32_t* entry) {
  return startTaskFrom(ctx, ctx.lookaheadIds, ctx.firstLookaheadId, level, g, entry);
}

// pt's answer to a MISSING brick a ray stops on, inside the march: noted; the ray claims it after
// the march (claimStop), once it knows it will wait for it (ptRunRay). Past the frame's deadline:
// startTaskAhead (those claims are no ray's, and could outnumber `freeIds`).
struct NoteMiss {
  const PtContext* ctx;
  bool missed = false;
  GVDP_HD void operator()(const CacheView&, int, Vec3i, uint32_t*) { missed = true; }
  GVDP_HD void ahead(const CacheView&, int level, Vec3i g, uint32_t* entry) const {
    startTaskAhead(*ctx, level, g, entry);
  }
};

// The claim of a MISSING brick a ray stopped on and will wait for: a task id from `freeIds`,
// waited for (one always comes: the capacity argument above), then startTask.
template <class Access>
GVDP_HD GVDP_INLINE void claimStop(const PtContext& ctx, const Access& a) {
  startTask(ctx, ringTake(ctx.freeIds, atomicAdd32(ctx.freeIds.head, 1u)), a.stopLevel,
            ctx.cache.clipmap.globalBrick(a.stopLevel, a.stopBrick), a.stopEntry);
}

// The answer of a march no ray waits for (the lookahead's, the prefetch's) to a MISSING brick:
// startTaskFrom its own ids, counted, at most `left` times, and only while half the frame's free
// slots are left (the frame's own productions must not fail for such claims).
struct StartAhead {
  const PtContext* ctx;
  const Ring* ids;
  uint32_t firstId;
  PtCounter counted;
  uint32_t left;
  bool endsWithRays;  // a prefetch's: see goesOn

  static GVDP_HD StartAhead lookahead(const PtContext& c, uint32_t bricks) {
    return {&c, &c.lookaheadIds, c.firstLookaheadId, PT_LOOKAHEAD, bricks, false};
  }
  // A far prefetch's marches all go on: its frame is idle (prefetchPlanAfter).
  static GVDP_HD StartAhead prefetch(const PtContext& c) {
    return {&c,
            &c.prefetchIds,
            c.firstPrefetchId,
            PT_PREFETCHES,
            MAX_LATE_CLAIMS,
            c.prefetchPoses == 1};
  }
  // Whether the march may enter another brick (cache/lookahead.h). A prefetch march enters none
  // after the frame's last ray has finished unless the frame's prefetch has claimed a brick: the
  // frame ends with its last march, and one of 64 bricks outlived the rays by up to 0.5 ms,
  // whatever it found (forest's walkthrough floor 5.31 ms, 4.79 without the prefetch in the floor's
  // frames). H100, 25 pt cells against marches that always go on: floors x0.958, FPS x0.999; ending
  // them unless a brick per 1024 prefetch rays was claimed cut aligned-spheres' walkthrough, which
  // lives on its prefetch, from 452 to 389-441 FPS (BENCHMARKS.md, session 22).
  GVDP_HD bool goesOn() const {
    return !endsWithRays || loadRelaxed32(ctx->counter(PT_LIVE_RAYS)) != 0 ||
           loadRelaxed32(ctx->counter(counted)) != 0;
  }
  GVDP_HD void operator()(const CacheView& cache, int level, Vec3i g, uint32_t* entry) {
    if (left == 0 || loadRelaxed32(&cache.counters[COUNTER_FREE_NEXT]) >= cache.freeCount() / 2)
      return;
    --left;
    if (startTaskFrom(*ctx, *ids, firstId, level, g, entry)) atomicAdd32(ctx->counter(counted), 1u);
  }
  GVDP_HD void ahead(const CacheView& cache, int level, Vec3i g, uint32_t* entry) {
    (*this)(cache, level, g, entry);
  }
};

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

// Parks a stopped ray (its state already saved) on the wait list of the task producing the
// brick it stopped on; false when there is no such task any more: the ray must march on.
GVDP_HD GVDP_INLINE bool parkRay(const PtContext& ctx, uint32_t pixel, const uint32_t* stopEntry) {
  uint32_t e = loadAcquire32(stopEntry);
  int64_t id = productionTaskOf(e);
  if (id < 0) return false;  // published (or MISSING again after a failure)
  // A stale id (the task finished and its id was reused) parks the ray on another task:
  // harmless, that task relaunches it too.
  uint32_t* head = &ctx.waitHead[id];
  uint32_t h = loadAcquire32(head);
  while (h != LIST_CLOSED) {
    storeRelaxed32(&ctx.waitNext[pixel], h);
    fenceSeqCst();  // the payload and the link before the push
    uint32_t seen = atomicCas32(head, h, pixel);
    if (seen == h) return true;
    h = seen;
  }
  return false;  // closed: the brick was published before the list closed
}

// How far a ray that stops again looks ahead: `lookahead`, or `tailLookahead` in the frame's
// tail, where the last chains of productions are what is left of the frame and few rays are left
// whose work the extra claims could delay; none while production tasks wait unclaimed in the
// queue or productions are open for helpers (PT_OPEN; the GPU's, 0 on the CPU): workers have
// production to take, its claims would only lengthen the queue, and its march run beside the
// productions crowds the instruction cache. In the frames that produce the most (a sphere exit, a
// spin) the worker was 77% of its stall samples waiting for instructions (ncu, random-spheres
// forward frame 17, H100). Off under a backlog: 25 pt cells FPS x1.039, 1% lows x1.100; and while
// productions are open: x1.045, x1.043 (BENCHMARKS.md, sessions 27 and 28).
//
// In the tail the lookahead also passes the bricks that are not resident instead of letting a
// coarser ancestor stand in: the last rays graze silhouettes, where a coarse ancestor is opaque
// and the ray at its own level passes beside the matter, so a stand-in ended the lookahead where
// the ray went on, to stop again on the next brick (the chains along silhouettes, session 48).
// H200, 25 pt cells, one binary with and without, 2 and 3 rounds: FPS x1.001 / x1.010, 1% lows
// x0.986 / x1.008, every random-spheres cell +2-5%, its walkthrough frame 12 5.2 -> 5.0 ms
// (BENCHMARKS.md, session 54).
struct LookaheadPlan {
  uint32_t bricks;
  int standInLevels;  // how far above a brick its stand-in may be (cache/lookahead.h)
};

GVDP_HD GVDP_INLINE LookaheadPlan lookaheadPlan(const PtContext& ctx) {
  if (loadRelaxed32(ctx.counter(PT_LIVE_RAYS)) <= ctx.tailRays) return {ctx.tailLookahead, 0};
  return {loadRelaxed32(ctx.tasks.ready) == 0 && loadRelaxed32(ctx.counter(PT_OPEN)) == 0
              ? ctx.lookahead
              : 0u,
          STAND_INS_ANY};
}

struct ParkOne {
  GVDP_HD bool operator()(const PtContext& ctx, uint32_t pixel, const uint32_t* stopEntry) const {
    return parkRay(ctx, pixel, stopEntry);
  }
  // Whether this ray looks ahead for the rays stopping on the same brick with it: alone, yes.
  GVDP_HD bool leads(const uint32_t*) const { return true; }
};

// How ptRunRay marches: its one ray on the thread (the CPU's workers), or a warp's rays together,
// until the first of them stops (pt_worker.cuh: WarpLanes).
struct OneLane {
  GVDP_HD bool any(bool live) const { return live; }
  template <class Access>
  GVDP_HD MarchResult march(const Ray& ray, const Lod& lod, RayState& s, Access& access,
                            bool) const {
    return detail::march(ray, lod, s, access);
  }
};

// Algorithm 1 for one ray (pixel < 0: none, for a lane of a warp that has none): marches until
// it finishes (true) or is parked (false). The Lanes march together while any of theirs is live;
// a march may end Paused (a warp's other ray stopped), and goes on. A ray that stops claims the
// brick if it was MISSING (claimStop: the claim's ring and task code stays out of the march's
// loop) and parks on its production: parkRay, or on the GPU a warp-aggregated version of it
// (pt_worker.cuh). A ray that stops again - after a relaunch (`relaunched`) or a failed park -
// first looks ahead (cache/lookahead.h), one ray for all those stopping on the same brick with
// it (Park::leads): a chain of waits is what the lookahead cuts, and a fresh ray's first stop is
// mostly on a brick its whole tile shares.
template <class Pool, class Park = ParkOne, class Lanes = OneLane>
GVDP_HD bool ptRunRay(const PtContext& ctx, const Pool& pool, int pixel, bool relaunched,
                      Park park = {}, Lanes lanes = {}) {
  const FrameSetup& f = ctx.frame;
  bool live = pixel >= 0, finished = false, again = relaunched;
  const uint32_t p = live ? static_cast<uint32_t>(pixel) : 0u;
  Ray ray = f.primaryRay(static_cast<int>(p) % f.width, static_cast<int>(p) / f.width);
  // A fresh ray starts afresh: its payload is the last frame's (no frame start writes them).
  RayState s = live && relaunched ? loadRayState(&ctx.payload[p]) : initialRayState();
  CachedAccess<Pool, NoteMiss> access{ctx.cache, pool, f.lod, NoteMiss{&ctx}};
  while (lanes.any(live)) {
    MarchResult r = lanes.march(ray, f.lod, s, access, live);
    if (!live || r == MarchResult::Paused) continue;
    storeRayState(&ctx.payload[p], s);
    if (r == MarchResult::Finished) {
      finished = true;
      live = false;
      continue;
    }
    if (access.onMiss.missed) claimStop(ctx, access);
    access.onMiss.missed = false;
    noteRayStop(ctx.cache, static_cast<int>(p));
    if (again && park.leads(access.stopEntry)) {
      LookaheadPlan plan = lookaheadPlan(ctx);
      lookAhead<PoolReads::Coherent>(ray, f.lod, s, ctx.cache, pool,
                                     StartAhead::lookahead(ctx, plan.bricks), plan.bricks,
                                     plan.standInLevels);
    }
    live = !park(ctx, p, access.stopEntry);
    again = true;
  }
  if (pixel >= 0) access.addCounts(pixel);
  return finished;
}

// No production's owner (a GPU warp's worker index, pt_worker.cuh), and no task id.
constexpr uint32_t NO_PRODUCTION = 0xffffffffu, PT_NO_TASK = 0xffffffffu;

// A GPU warp's role in a round of pt's loop (pt_worker.cuh: roleNow): Any takes any work; a
// Producer only produces (takes tasks, helps first, never renders); LeavesTasks renders, leaving
// tasks and help to the producers. With producer SMs (`share` S != 0), the warp of SM `sm` is a
// Producer while sm < ceil(backlog / S), the backlog being the tasks `ready` and those taken and
// not ended (`inFlight`), else LeavesTasks; every warp is Any without them, in a
// spike frame (`spike`: its backlog has reached `spikeBacklog`, the first warp to see it marks
// it), once a warp has left the loop (`exited`: the last worker left takes any task) and while
// tasks wait with no production in flight (unserved: the producer SMs' warps may all be
// rendering, or absent, since SM ids are not guaranteed dense; frame 0's first task, the eye's
// brick, waited 78 ms while every ray of the frame parked on it, whose wait list then took most
// of 300 ms to walk: BENCHMARKS.md, sessions 57-58).
enum class PtRole : uint32_t { Any, Producer, LeavesTasks };

GVDP_HD GVDP_INLINE PtRole ptRole(uint32_t share, uint32_t spikeBacklog, bool spike, uint32_t ready,
                                  uint32_t inFlight, uint32_t sm, bool exited) {
  const uint32_t backlog = ready + inFlight;
  const bool unserved = ready != 0 && inFlight == 0;
  if (share == 0 || spike || unserved || backlog >= spikeBacklog) return PtRole::Any;
  if (sm < (backlog + share - 1) / share) return PtRole::Producer;
  return exited ? PtRole::Any : PtRole::LeavesTasks;
}

// pt's worker loop, once for both backends: a worker (a CPU thread, or a GPU warp whose lanes all
// run it) takes, in this order, a production task, up to PT_BATCH relaunched rays, or the next
// PT_BATCH items of the screen (tile_order.h), until no ray or task of the frame is left; with none
// of those, it helps an open production, else marches PT_BATCH prefetch rays, else idles. A GPU
// warp of a helper SM (pt_worker.cuh: PT_HELPER_SMS) helps an open production before it takes
// rays or items; with producer SMs (pt_worker.cuh: roleNow), a warp of one only produces and the
// others leave the productions to them (renders, takesTasks). Both kinds of rays are run at one
// call site (render), so that the march is inlined once into the GPU kernel, and so are the samples
// of a production (help): a GPU warp's produce opens its production, whose samples it computes in
// the next round as any helper does (a second call site was a second copy of the producer in the
// worker: 54 KB of forest's SASS, 17 KB of random-spheres'; once: 25 pt cells FPS x1.017, 1% lows
// x1.029, H100, BENCHMARKS.md session 27). The Worker supplies the steps in its own scope
// (pt_cpu.cpp: a thread, whose produce does the whole production; pt_worker.cuh: a warp):
//   uint32_t liveWork()                                     the frame is over at 0
//   uint32_t claim(const Ring&, uint32_t n, uint32_t* pos)  ringClaim, result given to the scope
//   uint32_t producing()                                    its own open production (or none)
//   void produce(uint32_t position)                         the task at a claimed position
//   Batch queued(uint32_t position, uint32_t n)             n claimed relaunched rays
//   uint32_t claimFresh()                                   first item, itemCount when none is left
//   Batch fresh(uint32_t first)                             items first .. first + PT_BATCH - 1
//   void render(const Batch&)                               runs a batch's rays
//   uint32_t findProduction()                               one to help (NO_PRODUCTION: none)
//   bool helpsFirst()                                       helps before it renders
//   bool renders()                                          takes rays (false: only produces)
//   bool takesTasks()                                       takes production tasks and helps
//   void help(uint32_t owner)                               its samples; the end of its own
//   uint32_t claimPrefetch()                                first, prefetchItems when none
//   void prefetch(uint32_t first)                           prefetch rays first .. + PT_BATCH - 1
//   void idle(), finish()                                   nothing to take; the loop is over
template <class Worker>
GVDP_HD GVDP_INLINE void ptWorkerLoop(const PtContext& ctx, Worker& w) {
  while (w.liveWork() != 0) {
    uint32_t position = 0;
    typename Worker::Batch batch;
    uint32_t production = w.producing();
    const bool tasks = w.takesTasks();
    if (production == NO_PRODUCTION) {
      if (tasks && w.claim(ctx.tasks, 1, &position)) {
        w.produce(position);
        continue;
      }
      if (w.helpsFirst()) production = w.findProduction();
    }
    if (production == NO_PRODUCTION) {
      const bool renders = w.renders();
      if (uint32_t n = renders ? w.claim(ctx.rays, PT_BATCH, &position) : 0u) {
        batch = w.queued(position, n);
      } else if (uint32_t first = renders ? w.claimFresh() : ctx.itemCount; first < ctx.itemCount) {
        batch = w.fresh(first);
      } else if (!tasks || (production = w.findProduction()) == NO_PRODUCTION) {
        if (uint32_t p = renders ? w.claimPrefetch() : ctx.prefetchItems; p < ctx.prefetchItems)
          w.prefetch(p);
        else
          w.idle();
        continue;
      }
    }
    if (production != NO_PRODUCTION) {
      w.help(production);
      continue;
    }
    w.render(batch);
  }
  w.finish();
}

// The next PT_BATCH items of the screen for one claimant; itemCount when none is left.
GVDP_HD GVDP_INLINE uint32_t claimFreshItems(const PtContext& ctx) {
  if (loadRelaxed32(ctx.counter(PT_NEXT_ITEM)) >= ctx.itemCount) return ctx.itemCount;
  uint32_t first = atomicAdd32(ctx.counter(PT_NEXT_ITEM), static_cast<uint32_t>(PT_BATCH));
  return first < ctx.itemCount ? first : ctx.itemCount;
}

// The end of production task `id`, its rays queued again: the id back to its ring, the task off
// the frame's live work. Every task started is run before the frame ends: a brick claimed by a
// lookahead (or past a frame's budget) may have no ray waiting on it, and an entry left in
// production would stop the next frame's rays on a task that never comes.
GVDP_HD GVDP_INLINE void endTask(const PtContext& ctx, uint32_t id) {
  releaseTaskId(ctx, id);
  atomicAdd32(ctx.counter(PT_LIVE_WORK), 0u - 1u);
}

// One worker's single-threaded version of the end of a production task (CPU backend).
GVDP_HD GVDP_INLINE void finishProductionTask(const PtContext& ctx, uint32_t id) {
  const uint32_t relaunched = requeueRays(ctx, closeWaitList(ctx, id));
  atomicAdd32(ctx.counter(PT_RELAUNCHED), relaunched);
  atomicMax32(ctx.counter(PT_LONGEST_LIST), relaunched);
  endTask(ctx, id);
}

// A ring capacity for at most n items at once: a power of two > n.
GVDP_HD GVDP_INLINE uint32_t ringCapacity(uint32_t n) {
  uint32_t c = 1;
  while (c <= n) c <<= 1;
  return c;
}

// The sizes of pt's buffers for a frame of `pixels` rays and `workers` workers (the capacity
// argument at the top): the backends allocate them, the memory estimate adds them up.
struct PtLayout {
  uint32_t pixels, workers;

  GVDP_HD uint32_t freeIds() const {
    return pixels + workers;
  }  // ids of freeIds; then the lookahead's
  GVDP_HD uint32_t firstPrefetchId() const {
    return freeIds() + PT_LOOKAHEAD_IDS;
  }  // then the prefetch's
  GVDP_HD uint32_t taskIds() const { return firstPrefetchId() + PT_PREFETCH_IDS; }
  GVDP_HD uint32_t rayCapacity() const { return ringCapacity(pixels); }
  GVDP_HD uint32_t taskCapacity() const { return ringCapacity(taskIds()); }
  GVDP_HD uint32_t freeCapacity() const { return ringCapacity(freeIds()); }
  GVDP_HD static uint32_t lookaheadCapacity() { return ringCapacity(PT_LOOKAHEAD_IDS); }
  GVDP_HD static uint32_t prefetchCapacity() { return ringCapacity(PT_PREFETCH_IDS); }
  static constexpr size_t COUNTERS = size_t{PT_COUNTER_COUNT} * PT_COUNTER_STRIDE;
  size_t bytes() const {
    size_t slots = size_t{rayCapacity()} + taskCapacity() + freeCapacity() + lookaheadCapacity() +
                   prefetchCapacity();
    return slots * sizeof(uint64_t) + size_t{taskIds()} * (sizeof(BrickKey) + sizeof(uint32_t)) +
           size_t{pixels} * sizeof(uint32_t) + COUNTERS * sizeof(uint32_t);
  }
};

// Where a backend keeps pt's buffers, of the layout's sizes: the rings' slots, the task table and
// wait heads (taskIds), the wait links (pixels), the counters.
struct PtBuffers {
  uint64_t *raySlots, *taskSlots, *freeSlots, *lookaheadSlots, *prefetchSlots;
  BrickKey* taskKey;
  uint32_t *waitHead, *waitNext, *counters;
  PtLayout layout;
};

// The frame's context over a backend's buffers.
inline PtContext makePtContext(const FrameSetup& f, const CacheView& cache, RayState* payload,
                               const PtBuffers& b, uint32_t lookahead, uint32_t tailLookahead) {
  PtContext ctx{};
  ctx.frame = f;
  ctx.cache = cache;
  ctx.cache.degradeOnFailure = 1;
  ctx.payload = payload;
  ctx.counters = b.counters;
  auto ring = [&](uint64_t* slots, uint32_t capacity, PtCounter head) {
    return Ring{slots, capacity - 1, ctx.counter(head), ctx.counter(PtCounter(head + 1)),
                ctx.counter(PtCounter(head + 2))};
  };
  ctx.rays = ring(b.raySlots, b.layout.rayCapacity(), PT_RAY_HEAD);
  ctx.tasks = ring(b.taskSlots, b.layout.taskCapacity(), PT_TASK_HEAD);
  ctx.freeIds = ring(b.freeSlots, b.layout.freeCapacity(), PT_FREE_HEAD);
  ctx.lookaheadIds = ring(b.lookaheadSlots, PtLayout::lookaheadCapacity(), PT_LOOK_HEAD);
  ctx.firstLookaheadId = b.layout.freeIds();
  // A render from an empty cache (a degraded tile's retry, tiles/tiled_frame.cpp) overflows the
  // pool exactly when the bricks its rays need outnumber it, for every scheduler: claims ahead of
  // the rays would make that depend on the claims, hence on timing (pt's tiles of a 100-brick
  // forest differed from sp's once the all-zero bricks took no slots, H200).
  ctx.lookahead = f.coldCache ? 0u : lookahead;
  ctx.tailRays = static_cast<uint32_t>(f.pixelCount() / PT_TAIL_SHARE);
  ctx.tailLookahead = f.coldCache ? 0u : tailLookahead;
  ctx.prefetchIds = ring(b.prefetchSlots, PtLayout::prefetchCapacity(), PT_PREFETCH_HEAD);
  ctx.firstPrefetchId = b.layout.firstPrefetchId();
  ctx.taskKey = b.taskKey;
  ctx.waitHead = b.waitHead;
  ctx.waitNext = b.waitNext;
  ctx.itemCount = static_cast<uint32_t>(orderedItemCount(f));
  return ctx;
}

// The five rings, in the order of their counters: rays, tasks, freeIds, lookaheadIds, prefetchIds.
constexpr uint32_t PT_RINGS = 5;
constexpr uint32_t PT_FREE_RING = 2;

// The items ring r holds at a frame's start: the free task-id rings all their ids, the others none.
GVDP_HD GVDP_INLINE uint32_t ptRingFilled(uint32_t r, const PtLayout& layout) {
  return r == PT_FREE_RING ? layout.freeIds()
         : r == 3          ? PT_LOOKAHEAD_IDS
         : r == 4          ? PT_PREFETCH_IDS
                           : 0u;
}

// Counter word i at the start of a frame: every ray live, every task id free; a far prefetch's
// hold (claimPrefetchItems).
GVDP_HD GVDP_INLINE uint32_t initialPtCounter(size_t i, const PtLayout& layout, bool far) {
  if (i % PT_COUNTER_STRIDE != 0) return 0;
  const uint32_t k = static_cast<uint32_t>(i / PT_COUNTER_STRIDE);
  if (k < 3 * PT_RINGS) return k % 3 == 0 ? 0u : ptRingFilled(k / 3, layout);  // head; tail, ready
  const uint32_t hold = far ? 1u : 0u;
  return k == PT_LIVE_WORK   ? layout.pixels + hold
         : k == PT_LIVE_RAYS ? layout.pixels
         : k == PT_FAR_HOLD  ? hold
                             : 0u;
}

// The counter words from PT_FIRST_FRAME_COUNTER on start every frame afresh; those before it are
// the rings' (head, tail, ready), which a frame may take over from the last one (ptRingsQuiet).
constexpr size_t PT_FIRST_FRAME_COUNTER = size_t{PT_NEXT_ITEM} * PT_COUNTER_STRIDE;

// With `keepRings`, the frame's counters only (the rings as the last frame left them).
inline void initialPtCounters(uint32_t* c, const PtLayout& layout, bool keepRings = false,
                              bool far = false) {
  for (size_t i = keepRings ? PT_FIRST_FRAME_COUNTER : 0; i < PtLayout::COUNTERS; ++i)
    c[i] = initialPtCounter(i, layout, far);
}

// Whether a frame's rings, by their counters `c` at its end, are as a frame of `layout` starts
// them, up to where their positions stand: the ray and task rings empty, every task id back in
// its ring (the ids in any order). A Vyukov ring (Ring) left so serves its next laps as one whose
// slots were written afresh - its positions go on from where they stand, wrapping at 2^32, which
// its capacity divides - so the next frame of the same layout keeps it: writing every slot
// (6.3 M, 50 MB at 1500x1000) and every ray's payload (36 MB) took 40 us of each frame's start,
// 12% of aligned-spheres' 0.33 ms floor frame (`gvdp timeline --again`, H100). A frame that ended
// otherwise (an error, a bug: some id never given back) has its rings filled afresh.
inline bool ptRingsQuiet(const uint32_t* c, const PtLayout& layout) {
  for (uint32_t r = 0; r < PT_RINGS; ++r) {
    const uint32_t* w = c + size_t{3u * r} * PT_COUNTER_STRIDE;
    uint32_t head = w[0], tail = w[PT_COUNTER_STRIDE], ready = w[2 * PT_COUNTER_STRIDE];
    uint32_t filled = ptRingFilled(r, layout);
    // freeIds is taken at its head without a claim (claimStop): its `ready` only counts pushes.
    if (tail - head != filled || (r != PT_FREE_RING && ready != filled)) return false;
  }
  return true;
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

// The far prefetch (`farPoses` > 1, GVDP_PT_FAR): after an idle frame (no ray waited) whose view
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
// Session 57's dense start: floors x1.40, over-production 11.7%.
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
