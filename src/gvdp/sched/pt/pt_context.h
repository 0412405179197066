// A pt frame's shared state, the same on both backends: its counters, its five rings, the
// context every worker reads (PtContext), the buffers' sizes (PtLayout) and the counters at a
// frame's start. The protocol over them: pt_body.h.
#pragma once

#include "gvdp/cache/cache_view.h"
#include "gvdp/sched/pt/pt.h"
#include "gvdp/sched/pt/pt_ring.h"
#include "gvdp/sched/ray_tasks.h"
#include "gvdp/sched/tile_order.h"

namespace gvdp::detail {

constexpr uint32_t LIST_END = 0xffffffffu, LIST_CLOSED = 0xfffffffeu;
constexpr int PT_BATCH = 32;                     // rays per render task (a warp)
constexpr int PT_COUNTER_STRIDE = 32;            // counters sit 128 bytes apart (no false sharing)
constexpr uint32_t PT_LOOKAHEAD_IDS = 1u << 15;  // task ids for the lookahead's claims
constexpr uint32_t PT_PREFETCH_IDS = 1u << 14;   // task ids for the prefetch's claims

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
  uint32_t spikeBacklog;           // the backlog from which a frame is a spike (the same)
  uint32_t spikeProducers;         // the SMs that only produce in a spike frame (the same)
  // The prefetch's predicted frames (a far prefetch: more than one), their cameras (the next
  // frame's first, nearGrid's rays; the others farGrid's each), and a far prefetch's claims at
  // most.
  uint32_t prefetchPoses = 1;
  PrefetchPose poses[PT_FAR_MAX_POSES];
  uint32_t farClaims = 0;

  GVDP_HD uint32_t* counter(PtCounter c) const { return &counters[c * PT_COUNTER_STRIDE]; }
};

// The sizes of pt's buffers for a frame of `pixels` rays and `workers` workers (the capacity
// argument at the top of pt_body.h): the backends allocate them, the memory estimate adds them up.
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

}  // namespace gvdp::detail
