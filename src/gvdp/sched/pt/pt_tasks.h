// pt's production tasks: claiming a MISSING brick under a task id (startTask), the wait list a
// stopped ray parks on (parkRay) and the end of a task that queues its rays again (endTask);
// the claims of marches no ray waits for (StartAhead: the lookahead's, the prefetch's).
#pragma once

#include "gvdp/cache/cached_access.h"
#include "gvdp/sched/pt/pt_context.h"

namespace gvdp::detail {

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
// without one the brick stays MISSING. True when this claim started the task. The one attempt is
// a throttle that helps: a warp's lanes race for it and most lose (random-spheres' frame 12:
// ~2 650 turned down, ~1 500 made), and retrying while ids were ready claimed 30% more in the
// tail, whose rays then waited on those productions instead: 25 pt cells FPS x0.991, 1% lows
// x0.964 (H200, BENCHMARKS.md session 72).
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
// waited for (one always comes: the capacity argument at the top of pt_body.h), then startTask.
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
  bool endsWithRays;  // see goesOn

  static GVDP_HD StartAhead lookahead(const PtContext& c, uint32_t bricks) {
    return {&c, &c.lookaheadIds, c.firstLookaheadId, PT_LOOKAHEAD, bricks, true};
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
  // Whether the march may enter another brick (cache/lookahead.h). A lookahead enters none
  // after the frame's last ray has finished: its ray parked before it looked ahead (ptRunRay), so
  // that ray, the frame's last, may finish while the march goes on, and what the march would
  // claim then only holds the frame open. A prefetch march enters none after the frame's last
  // ray has finished unless the frame's prefetch has claimed a brick: the frame ends with its
  // last march, and one of 64 bricks outlived the rays by up to 0.5 ms, whatever it found
  // (forest's walkthrough floor 5.31 ms, 4.79 without the prefetch in the floor's frames). H100,
  // 25 pt cells against marches that always go on: floors x0.958, FPS x0.999; ending them unless
  // a brick per 1024 prefetch rays was claimed cut aligned-spheres' walkthrough, which lives on
  // its prefetch, from 452 to 389-441 FPS (BENCHMARKS.md, session 22).
  GVDP_HD bool goesOn() const {
    if (!endsWithRays || loadRelaxed32(ctx->counter(PT_LIVE_RAYS)) != 0) return true;
    return counted == PT_PREFETCHES && loadRelaxed32(ctx->counter(counted)) != 0;
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

}  // namespace gvdp::detail
