// The persistent-threads scheduler (pt) as one protocol for both backends: workers (GPU warps,
// CPU threads) pull tasks from device work queues until every ray of the frame has finished and
// every production task started in it has run.
//
// Queues (lock-free rings of uint32, one atomic per batch):
//   tasks    production task ids, served first, in the order claimed (rays' stops and the claims
//            ahead of the rays in one FIFO: either kind first was no faster, BENCHMARKS.md
//            session 66);
//   rays     pixels of relaunched rays, taken 32 at a time (full warps, seed 004);
//   fresh    the screen itself, 8x4-pixel halves of the 8x8 tiles, through a counter.
// A ray that finds a brick MISSING takes a task id from the `freeIds` ring and claims the brick
// with a CAS from MISSING to the task's name (ENTRY_PRODUCTION_TASK + id); the winner queues
// the task, a loser gives the id back. A ray that stops on a brick in
// production parks itself on that task's wait list (a lock-free stack through `waitNext`);
// the production closes the list after publishing the brick and queues its rays as full warps.
// A push onto a closed list fails and the ray marches on: no ray is ever lost or held twice.
//
// A stopped ray, once parked, looks ahead (cache/lookahead.h): it claims up to `lookahead` more
// missing bricks on its path, each with an id from a ring of its own (`lookaheadIds`), taken only
// when one is ready (never waited for): without an id the brick stays MISSING for a ray to claim.
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
// composited. A far prefetch (--far-prefetch, off by default: prefetchPlanAfter) marches several
// predicted frames after an idle one with a closed view.
//
// Capacities, not guesses: a ray is in at most one place (running, in `rays`, or on one list),
// so `rays` holds at most `pixels` items; every unfinished task from `freeIds` has its winning
// ray parked on it or about to be, so at most pixels + workers of those ids are out at once, and
// a ray that needs one always gets one (it waits only for a task in flight to finish). Claims
// no ray waits for (the lookahead's, and those past a budgeted frame's deadline) take ids from a
// separate ring of PT_LOOKAHEAD_IDS, only when one is ready. `tasks` holds at most all ids.
#pragma once

#include "gvdp/cache/lookahead.h"
#include "gvdp/sched/pt/pt_context.h"
#include "gvdp/sched/pt/pt_prefetch.h"
#include "gvdp/sched/pt/pt_tasks.h"

namespace gvdp::detail {

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
//
// In the tail only a ray that parked looks ahead: one whose park failed (its brick was published
// while it claimed it) marches on at once, since its lookahead walked the ray's own next bricks
// while the ray waited for it (57-60 us for a tail lookahead in random-spheres' walkthrough frame
// 12, against 7-12 us for the stop's claim and park, H200, session 75), and a parked ray looks
// ahead off its path. H200, main against the rule: that frame 5.03 -> 4.86 ms, idle 10.8 -> 8.9%;
// 25 pt cells FPS x1.004, 1% lows x1.005, every random-spheres cell's FPS up (BENCHMARKS.md
// session 75).
struct LookaheadPlan {
  uint32_t bricks;
  int standInLevels;  // how far above a brick its stand-in may be (cache/lookahead.h)
};

GVDP_HD GVDP_INLINE LookaheadPlan lookaheadPlan(const PtContext& ctx, bool parked) {
  if (loadRelaxed32(ctx.counter(PT_LIVE_RAYS)) <= ctx.tailRays)
    return {parked ? ctx.tailLookahead : 0u, 0};
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
// then looks ahead (cache/lookahead.h) from its state, one ray for all those stopping on the same
// brick with it (Park::leads): a chain of waits is what the lookahead cuts, and a fresh ray's
// first stop is mostly on a brick its whole tile shares. It parks first: a parked ray is
// relaunched once its brick is produced, whatever its old lane is doing, so the lookahead is off
// its path. Looking ahead first, a ray waited for its lookahead's march and claims, which in the
// tail took longer than its brick's production: 73-104 us for a tail lookahead of 14-17 bricks in
// random-spheres' walkthrough frames 10-14, against ~28 us for a production. Parking first: 25 pt
// cells FPS x1.002-1.005, every random-spheres cell +1-3% in three calls, its frame 12 5.09-5.15
// -> 5.00-5.02 ms, the same images (H200, BENCHMARKS.md session 70). In the frame's tail a ray
// whose park failed does not look ahead (lookaheadPlan).
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
    const bool looks = again && park.leads(access.stopEntry);
    live = !park(ctx, p, access.stopEntry);
    if (looks) {  // on this lane's copy of the state: a parked ray may run elsewhere
      LookaheadPlan plan = lookaheadPlan(ctx, !live);
      lookAhead<PoolReads::Coherent>(ray, f.lod, s, ctx.cache, pool,
                                     StartAhead::lookahead(ctx, plan.bricks), plan.bricks,
                                     plan.standInLevels);
    }
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
// not ended (`inFlight`), else LeavesTasks. In a spike frame (`spike`: its backlog has reached
// `spikeBacklog`, the first warp to see it marks it) the split is fixed instead: SMs below
// `spikeProducers` produce and the others render, so that the rays which find the frame's
// missing bricks keep running (every SM producing made random-spheres' 267 000-brick frame 82 ms
// against 47: session 40); with spikeProducers 0, every warp is Any there. Every warp is Any
// without producer SMs, once a warp has left the loop (`exited`: the last worker left takes any
// task) and while tasks wait with no production in flight (unserved: the producer SMs' warps may
// all be rendering, or absent, since SM ids are not guaranteed dense; frame 0's first task, the
// eye's brick, waited 78 ms while every ray of the frame parked on it, whose wait list then took
// most of 300 ms to walk: BENCHMARKS.md, sessions 57-58).
enum class PtRole : uint32_t { Any, Producer, LeavesTasks };

GVDP_HD GVDP_INLINE PtRole ptRole(uint32_t share, uint32_t spikeBacklog, uint32_t spikeProducers,
                                  bool spike, uint32_t ready, uint32_t inFlight, uint32_t sm,
                                  bool exited) {
  const uint32_t backlog = ready + inFlight;
  const bool unserved = ready != 0 && inFlight == 0;
  if (share == 0 || unserved) return PtRole::Any;
  bool produces = false;
  if (spike || backlog >= spikeBacklog) {
    if (spikeProducers == 0) return PtRole::Any;
    produces = sm < spikeProducers;
  } else {
    // sm < ceil(backlog / S) without a division: it ran in every round of every warp's loop, 20
    // instructions of lane 0 (2.6-3.8% of the worker's instructions in frames that produce, ncu).
    produces = uint64_t{sm} * share < backlog;
  }
  if (produces) return PtRole::Producer;
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

}  // namespace gvdp::detail
