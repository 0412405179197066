// The persistent kernel of the pt scheduler: every warp is a worker of pt's loop (pt_body.h) that
// takes a production task (the warp produces the brick: 1000 samples over 32 lanes), up to 32
// relaunched rays, or the next 8x4 pixels of the screen (its costliest blocks first: tile_order.h),
// until no ray or task of the frame is left.
// Timeline records are per warp: a span of consecutive tasks of one kind, closed when the warp
// switches kind or finds no work (idle warps are idle on the timeline). A template on the
// producer (producer_kernels_of.h); the frame's start (rings, payloads, counters) is in
// pt_kernels.cu.
#pragma once

#include "gvdp/base/bits.h"
#include "gvdp/base/cuda_util.h"
#include "gvdp/base/dependent_launch.cuh"
#include "gvdp/cache/produce.h"
#include "gvdp/profile/timeline_device.cuh"
#include "gvdp/render/brick_pool.h"
#include "gvdp/render/march_warp.cuh"
#include "gvdp/sched/pt/pt_body.h"

namespace gvdp::detail {

// 3 blocks of 8 warps per SM (80 registers): measured on an H100 against 2 (125 registers) and
// 4 (64, spilling), perlin 1500x1000: 24 ms per frame against 39 and 25; 7 blocks of 4 warps (72
// registers): 25 pt cells' floors x0.974, FPS x0.988 (BENCHMARKS.md, session 22).
constexpr int PT_BLOCK = 256, PT_WARPS = PT_BLOCK / 32, PT_MIN_BLOCKS = 3;
static_assert(PT_WARPS == static_cast<int>(PT_WORKER_WARPS));
constexpr unsigned FULL_MASK = 0xffffffffu;
// Helper SMs: one SM in PT_HELPER_SMS (smId() % PT_HELPER_SMS == 0), whose warps help an open
// production before they take relaunched rays or screen items; the other SMs' warps help only with
// nothing else to take. A production then gets helpers while the screen is still being rendered,
// and its rays wait for 32 chunks computed by many warps rather than by its owner alone. H100,
// 25 pt cells, three calls of 2 rounds: FPS x1.053-1.060, 1% lows x1.066-1.086 (perlin's
// walkthrough frame 12: 4.2 -> 3.6 ms); one SM in 2: x1.004, in 3: x1.044, in 6: x1.062, in 8:
// x1.060; a quarter of every SM's warps instead of a quarter of the SMs: x0.997 (BENCHMARKS.md,
// session 33).
constexpr uint32_t PT_HELPER_SMS = 4;
// An idle warp's sleeps, ns: doubled from the shortest to the longest while it finds nothing.
constexpr unsigned PT_SHORTEST_SLEEP = 32, PT_LONGEST_SLEEP = 1024;

// Lane 0's open timeline span, kept in the warp's shared memory: in registers (with a copy of the
// timeline's view) it was live across the march (80 registers: spill stores 784 -> 664 bytes).
struct WarpSpan {
  uint64_t start, end;
  TaskKind kind;
  bool open;
  bool fresh;  // open, and no task done in it yet

  __device__ void begin(const TimelineView& timeline, TaskKind k) {
    if (open && k == kind) return;
    close(timeline);
    kind = k;
    start = clockNanoseconds();
    open = true;
    fresh = true;
  }
  __device__ void taskDone() {
    end = clockNanoseconds();
    fresh = false;
  }
  // A round that did nothing (a helper that found every chunk claimed): its time is not work. A
  // span it opened is dropped; one open before it ends at its last task.
  __device__ void nothingDone(const TimelineView& timeline) {
    if (open && fresh)
      open = false;
    else
      close(timeline);
  }
  __device__ void close(const TimelineView& timeline) {
    if (!open) return;
    uint16_t sm = static_cast<uint16_t>(smId());
    timeline.push({start, end, sm, sm, kind});
    open = false;
  }
};

// What a worker warp keeps in shared memory: the march's staging (render/march_warp.cuh) and lane
// 0's timeline span.
struct WarpWorkerShared {
  WarpMarchShared march;
  WarpSpan span;
  // Lane 0's alone: the render's start (SM cycles) and the fresh batch's first item (-1:
  // relaunched rays).
  uint32_t costStart;
  int costFirst;
  // Lane 0's alone (read through fromLane0): the task whose production this warp opened
  // (PT_NO_TASK: none) and whether it has chunks (false: the box bound cleared its brick).
  uint32_t ownTask;
  bool ownChunks;
};

__device__ inline uint32_t warpClaim(const Ring& r, uint32_t n, uint32_t* position, int lane) {
  uint32_t got = 0, pos = 0;
  if (lane == 0) got = ringClaim(r, n, &pos);
  *position = __shfl_sync(FULL_MASK, pos, 0);
  return __shfl_sync(FULL_MASK, got, 0);
}

// parkRay for the lanes of a warp that stop together: the lanes parking on one task link
// themselves into a chain that one CAS pushes, instead of one CAS each on the same list head (a
// brick with 100 000 waiting rays cost 50 ms of serialised CAS, measured).
struct ParkWarp {
  __device__ bool operator()(const PtContext& ctx, uint32_t pixel,
                             const uint32_t* stopEntry) const {
    int64_t task = productionTaskOf(loadAcquire32(stopEntry));
    uint32_t id = task < 0 ? LIST_END : static_cast<uint32_t>(task);
    unsigned group = __match_any_sync(__activemask(), id);
    if (task < 0) return false;  // published (or MISSING again): march on
    int lane = static_cast<int>(threadIdx.x & 31), leader = lowestBit(group);
    unsigned above = group & ~((2u << lane) - 1u);
    uint32_t next = __shfl_sync(group, pixel, above ? lowestBit(above) : lane);
    uint32_t last = __shfl_sync(group, pixel, 31 - __clz(static_cast<int>(group)));
    if (above) storeRelaxed32(&ctx.waitNext[pixel], next);
    __threadfence();
    __syncwarp(group);
    bool parked = false;
    if (lane == leader) {  // the chain: leader -> ... -> last -> the list
      uint32_t* head = &ctx.waitHead[id];
      uint32_t h = loadAcquire32(head);
      while (h != LIST_CLOSED) {
        storeRelaxed32(&ctx.waitNext[last], h);
        __threadfence();
        uint32_t seen = atomicCAS(head, h, pixel);
        if (seen == h) {
          parked = true;
          break;
        }
        h = seen;
      }
    }
    return __shfl_sync(group, parked, leader);
  }

  // One lane of those that stopped on the same brick together looks ahead.
  __device__ bool leads(const uint32_t* stopEntry) const {
    unsigned group =
        __match_any_sync(__activemask(), reinterpret_cast<unsigned long long>(stopEntry));
    return static_cast<int>(threadIdx.x & 31) == lowestBit(group);
  }
};

// ptRunRay's march of a warp's rays: together, their samples shared out (render/march_warp.cuh),
// until the first of them stops; the stopped rays then claim, look ahead and park at once, and
// the others march on together (a failed park rejoins them). (Marching together until every ray
// had stopped or ended, the stopped ones waited for the others: perlin forward 417 -> 336 FPS;
// each lane marching on by itself after the first stop: FPS x0.79; H100, BENCHMARKS.md.)
struct WarpLanes {
  WarpMarchShared* shared;  // the warp's
  __device__ bool any(bool live) const { return __any_sync(FULL_MASK, live); }
  template <class Access>
  __device__ MarchResult march(const Ray& ray, const Lod& lod, RayState& s, Access& access,
                               bool live) const {
    return marchWarp<WarpMarchEnd::FirstStop>(ray, lod, s, access, live, *shared);
  }
};

__device__ inline void renderLanes(const PtContext& ctx, const BrickPool& pool, int pixel,
                                   bool relaunched, int lane, WarpMarchShared* shared) {
  bool finished = ptRunRay(ctx, pool, pixel, relaunched, ParkWarp{}, WarpLanes{shared});
  unsigned done = __ballot_sync(FULL_MASK, finished);
  if (lane == 0) {
    if (done) {
      atomicSub(ctx.counter(PT_LIVE_RAYS), static_cast<uint32_t>(__popc(done)));
      atomicSub(ctx.counter(PT_LIVE_WORK), static_cast<uint32_t>(__popc(done)));
    }
    atomicAdd(ctx.counter(PT_RENDER_TASKS), 1u);
  }
}

// Productions in flight (PtProductions, in device memory), whose chunks (one sample per lane)
// any warp of the grid may compute: the owner warp computes chunks until none is left, then waits
// for its helpers. Only the warps of helper SMs (PT_HELPER_SMS) and warps with nothing else to
// take help (every warp helping before it rendered halved production throughput, measured), their
// own block's productions first; in the frame's tail, a chain of dependent productions, up to 32
// warps of any SMs compute one brick at once (a block's 8 warps, 4 samples a lane, before: mesh
// bricks of 5-20 ms each made a 54 ms tail, measured).
//
// Warps of different blocks hand these words to each other, so every access is a strong one at
// device scope: writes are atomic exchanges, read-modify-writes or relaxed stores, reads relaxed
// loads, and release/acquire pairs order the data: the owner publishes key and counters (fence,
// then `next`, then its `open` bit), a helper acquires them by claiming its first chunk (atomic
// on `next`, then fence); every lane of a helper fences its samples before lane 0 counts its
// chunks in `done`, and the owner acquires them by reading `done` (then every lane fences). A
// production is reused only by its owner, after its last chunk is done; a helper that claims past
// the last chunk (a stale `open` bit) does nothing.
constexpr int PRODUCE_CHUNK = 32, PRODUCE_CHUNKS = (BRICK_SAMPLE_COUNT + 31) / 32;

// A strong store of a word that other warps read without a barrier.
__device__ inline void handOver(uint32_t* word, uint32_t value) {
  atomicExch(word, value);
}

__device__ inline void handOverKey(BrickKey* key, const BrickKey& value) {
  uint32_t* k = reinterpret_cast<uint32_t*>(key);
  handOver(k, static_cast<uint32_t>(value.brick.x));
  handOver(k + 1, static_cast<uint32_t>(value.brick.y));
  handOver(k + 2, static_cast<uint32_t>(value.brick.z));
  handOver(k + 3, static_cast<uint32_t>(value.level));
}

__device__ inline uint32_t workerOf(int warp) {
  return blockIdx.x * PT_WORKER_WARPS + static_cast<uint32_t>(warp);
}

// Claims and computes chunks of worker `owner`'s production until none is left, then publishes
// them (samples, nonEmpty, `done`) at once. Until then the owner cannot close the production, so
// every chunk the warp claims is of the same one: one acquire and one key load a call, and each
// next claim is in flight while the chunk before it is computed. Returns the chunks it computed
// (0: every chunk was claimed before it came).
template <class P>
__device__ uint32_t produceChunks(const P& producer, const PtProductions& pp, uint32_t owner,
                                  int lane) {
  uint32_t c = 0;
  if (lane == 0) {
    c = atomicAdd(&pp.next[owner], 1u);
    __threadfence();  // acquire: the key the owner wrote before opening the production
  }
  c = __shfl_sync(FULL_MASK, c, 0);
  if (c >= static_cast<uint32_t>(PRODUCE_CHUNKS)) return 0;
  __syncwarp();  // lane 0's acquire before every lane's read of the key
  const BrickKey key = loadBrickKey(&pp.key[owner]);
  uint32_t chunks = 0;
  bool nonEmpty = false;
  do {
    uint32_t next = 0;
    if (lane == 0) {
      // The last chunk is taken: no more help (helpers would spin on an exhausted production).
      if (c == PRODUCE_CHUNKS - 1) {
        atomicAnd(&pp.open[owner / 32], ~(1u << owner % 32));
        atomicSub(pp.openCount, 1u);
      }
      next = atomicAdd(&pp.next[owner], 1u);
    }
    int s = static_cast<int>(c) * PRODUCE_CHUNK + lane;
    if (s < BRICK_SAMPLE_COUNT) {
      VoxelSample v = produceBrickSample(producer, key, s);
      storeRelaxed32(&pp.stage[size_t{owner} * BRICK_SAMPLE_COUNT + s], v.rgba);
      nonEmpty = nonEmpty || !v.empty;
    }
    ++chunks;
    c = __shfl_sync(FULL_MASK, next, 0);
  } while (c < static_cast<uint32_t>(PRODUCE_CHUNKS));
  nonEmpty = __any_sync(FULL_MASK, nonEmpty);
  __threadfence();  // release: this lane's samples before `done`
  __syncwarp();
  if (lane == 0) {
    if (nonEmpty) atomicOr(&pp.nonEmpty[owner], 1u);
    __threadfence();  // release: nonEmpty before `done`
    atomicAdd(&pp.done[owner], chunks);
  }
  return chunks;
}

// The start of Algorithm 2 by warp `warp`: task `id`'s key and counters in its worker's production,
// opened to helpers, unless the producer's box bound clears the brick (false: no chunks, the brick
// is committed EMPTY by closeProductionTask). The warp computes its chunks in the worker loop's
// next round, as a helper does (pt_body.h: ptWorkerLoop), so the producer is inlined once.
template <class P>
__device__ bool openProductionTask(const PtContext& ctx, const P& producer, uint32_t id, int warp,
                                   int lane) {
  const PtProductions& pp = ctx.productions;
  const uint32_t me = workerOf(warp);
  BrickKey key = loadTaskKey(ctx, id);
  if (brickBoundedEmpty(WarpScope{lane}, producer, key)) return false;
  if (lane == 0) {  // no helper is in this production's words: the last one counted its chunk
    handOverKey(&pp.key[me], key);
    handOver(&pp.nonEmpty[me], 0u);
    handOver(&pp.done[me], 0u);
    __threadfence();  // release: key and counters before the first claim
    atomicExch(&pp.next[me], 0u);
    atomicAdd(pp.openCount, 1u);  // before the bit, so before any helper's decrement
    __threadfence();
    atomicOr(&pp.open[me / 32], 1u << me % 32);
  }
  __syncwarp();
  return true;
}

// The end of Algorithm 2 by warp `warp`, its chunks computed: the helpers' chunks waited for, the
// brick committed, then the task's waiting rays queued again as full warps (an EMPTY brick's box
// is grown after its rays are queued).
template <class P>
__device__ void closeProductionTask(const PtContext& ctx, const BrickPool& pool, const P& producer,
                                    uint32_t id, bool chunks, int warp, int lane) {
  const PtProductions& pp = ctx.productions;
  const uint32_t me = workerOf(warp);
  BrickKey key = loadTaskKey(ctx, id);
  bool empty = true;
  if (chunks) {
    if (lane == 0) {
      while (loadRelaxed32(&pp.done[me]) < static_cast<uint32_t>(PRODUCE_CHUNKS)) __nanosleep(20);
      __threadfence();  // acquire: every helper's samples
    }
    __syncwarp();
    __threadfence();  // and for every lane that reads them
    empty = loadRelaxed32(&pp.nonEmpty[me]) == 0;
  }
  const Rgba8* stage = pp.stage + size_t{me} * BRICK_SAMPLE_COUNT;
  constexpr int PER = (BRICK_SAMPLE_COUNT + 31) / 32;
  // An EMPTY brick's rays go on before its box is grown: it is published EMPTY alone first, its
  // rays are queued, and publishEmpty then grows its box, marks the box's members and ancestors
  // and publishes it again with the box (either entry says EMPTY; the box only lets rays skip
  // more). The growth is rounds of bound tests that the rays waited for (sessions 29, 36, 52).
  if (!empty)
    commitSamples<PER>(WarpScope{lane}, ctx.cache, pool, key,
                       [&](int, int s) { return loadRelaxed32(&stage[s]); });
  else if (lane == 0)
    publishEmptyAlone(ctx.cache, key);
  __syncwarp();
  if (lane == 0) markIfPrefetched(ctx, id, key);
  uint32_t p = 0;
  if (lane == 0) p = closeWaitList(ctx, id);
  p = __shfl_sync(FULL_MASK, p, 0);
  uint32_t relaunched = 0;
  while (p != LIST_END) {  // the list is stable: none of its rays runs until queued
    uint32_t mine = LIST_END;
    for (int k = 0; k < 32 && p != LIST_END; ++k) {
      if (lane == k) mine = p;
      p = loadRelaxed32(&ctx.waitNext[p]);
    }
    unsigned m = __ballot_sync(FULL_MASK, mine != LIST_END);
    uint32_t base = 0;
    if (lane == 0) base = ringReserve(ctx.rays, static_cast<uint32_t>(__popc(m)));
    base = __shfl_sync(FULL_MASK, base, 0);
    if (mine != LIST_END) ringStore(ctx.rays, base + __popc(m & ((1u << lane) - 1u)), mine);
    __syncwarp();
    if (lane == 0) ringPublish(ctx.rays, static_cast<uint32_t>(__popc(m)));
    relaunched += static_cast<uint32_t>(__popc(m));
  }
  if (empty) publishEmpty(WarpScope{lane}, producer, ctx.cache, key);
  if (lane == 0) {
    atomicAdd(ctx.counter(PT_RELAUNCHED), relaunched);
    atomicMax(ctx.counter(PT_LONGEST_LIST), relaunched);
    atomicAdd(ctx.counter(PT_PRODUCTIONS), 1u);
    if (ctx.producerShare != 0) atomicSub(ctx.counter(PT_IN_FLIGHT), 1u);
    endTask(ctx, id);
  }
}

// An open production for an idle warp to help: one of its own block's, else the first found in
// the grid's `open` bits, read from its own block's word on (blocks start their search apart).
// The search runs only while the count of open productions is nonzero: an idle warp's poll is
// then a few loads (in a floor frame of random-spheres, H100, the search of every poll was 17% of
// the worker kernel's instructions, issued beside the warps still marching).
__device__ inline uint32_t openProduction(const PtProductions& pp, int lane) {
  const uint32_t first = workerOf(0), home = first / 32;
  uint32_t own = 0, count = 0;
  if (lane == 0) {
    count = loadRelaxed32(pp.openCount);
    own = loadRelaxed32(&pp.open[home]) >> first % 32 & ((1u << PT_WORKER_WARPS) - 1u);
  }
  own = __shfl_sync(FULL_MASK, own, 0);
  if (own) return first + static_cast<uint32_t>(lowestBit(own));
  if (__shfl_sync(FULL_MASK, count, 0) == 0) return NO_PRODUCTION;
  for (uint32_t base = 0; base < pp.openWords; base += 32) {
    uint32_t k = base + static_cast<uint32_t>(lane), w = home + k;
    w = w < pp.openWords ? w : w - pp.openWords;  // (home + k) mod openWords: both below it
    uint32_t bits = k < pp.openWords ? loadRelaxed32(&pp.open[w]) : 0u;
    unsigned any = __ballot_sync(FULL_MASK, bits != 0u);
    if (any) {
      int src = lowestBit(any);
      uint32_t word = __shfl_sync(FULL_MASK, w, src), b = __shfl_sync(FULL_MASK, bits, src);
      return word * 32 + static_cast<uint32_t>(lowestBit(b));
    }
  }
  return NO_PRODUCTION;
}

// One worker (a warp) of pt's loop (pt_body.h): every lane runs every step, lane 0 claims and
// shares what it claimed. With nothing to take, or on a helper or producer SM before it renders,
// the warp helps a production (its block's first); with nothing to take, else it marches prefetch
// rays, or sleeps with an exponential backoff. Its role (roleNow) is read with the live work at
// the top of every round.
template <class P>
struct WarpWorker {
  const PtContext& ctx;
  const BrickPool& pool;
  const P& producer;
  int lane;
  WarpWorkerShared& shared;  // the warp's: little of the worker's own lives in registers across
                             // the march (WarpSpan)
  unsigned backoff = PT_SHORTEST_SLEEP;  // ns
  PtRole role = PtRole::Any;             // this round's (roleNow)

  // What lane 0 finds, for every lane.
  template <class F>
  __device__ uint32_t fromLane0(F f) const {
    uint32_t v = 0;
    if (lane == 0) v = f();
    return __shfl_sync(FULL_MASK, v, 0);
  }
  // The frame's live work; the warp's role for this round of the loop.
  __device__ uint32_t liveWork() {
    uint32_t live = 0, r = 0;
    if (lane == 0) {
      live = loadRelaxed32(ctx.counter(PT_LIVE_WORK));
      r = static_cast<uint32_t>(roleNow());
    }
    role = static_cast<PtRole>(__shfl_sync(FULL_MASK, r, 0));
    return __shfl_sync(FULL_MASK, live, 0);
  }
  __device__ uint32_t claim(const Ring& r, uint32_t n, uint32_t* position) const {
    return warpClaim(r, n, position, lane);
  }
  __device__ uint32_t producing() const {
    return fromLane0([&] { return shared.ownTask; }) == PT_NO_TASK ? NO_PRODUCTION
                                                                   : workerOf(warp());
  }
  __device__ void produce(uint32_t position) {
    begin(TaskKind::Produce);
    uint32_t id = 0;
    if (lane == 0) id = ringTake(ctx.tasks, position);
    id = __shfl_sync(FULL_MASK, id, 0);
    bool chunks = openProductionTask(ctx, producer, id, warp(), lane);
    if (lane == 0) {
      if (ctx.producerShare != 0) atomicAdd(ctx.counter(PT_IN_FLIGHT), 1u);
      shared.ownTask = id;
      shared.ownChunks = chunks;
    }
  }
  // This lane's ray of a batch (-1: none).
  struct Batch {
    int pixel = -1;
    bool relaunched = false;
    int first = 0;  // a fresh batch's first item (its cost is its tile's)
  };
  __device__ Batch queued(uint32_t position, uint32_t n) {
    begin(TaskKind::Render);
    return {lane < static_cast<int>(n) ? static_cast<int>(ringTake(ctx.rays, position + lane)) : -1,
            true};
  }
  __device__ uint32_t claimFresh() const {
    return fromLane0([&] { return claimFreshItems(ctx); });
  }
  __device__ Batch fresh(uint32_t first) {
    begin(TaskKind::Render);
    uint32_t item = first + static_cast<uint32_t>(lane);
    return {orderedPixel(ctx.frame, ctx.tiles, static_cast<int>(item)), false,
            static_cast<int>(first)};
  }
  __device__ void render(const Batch& b) {
    if (lane == 0) {
      shared.costFirst = b.relaunched ? -1 : b.first;
      shared.costStart = smCycles();
    }
    renderLanes(ctx, pool, b.pixel, b.relaunched, lane, &shared.march);
    if (lane == 0 && shared.costFirst >= 0)
      noteBlockCost(ctx.tiles, shared.costFirst, smCycles() - shared.costStart);
    worked();
  }
  __device__ uint32_t findProduction() const { return openProduction(ctx.productions, lane); }
  // Producer SMs (PtContext::producerShare = S: 2 unless GVDP_PT_PRODUCER_SHARE says): SMs 0 ..
  // ceil(backlog / S) - 1, the backlog being the tasks queued and the productions taken and not
  // ended, only produce; their warps help before anything else. Every SM's instruction caches
  // then hold the production code or the march, not both (a growth round on one warp: 1.9 us
  // alone, 34 us among 24 warps an SM of other code; session 38). The other warps leave tasks and
  // productions to them, except a warp that has idled to its longest sleep (no SM id below the
  // count may be running: ids are not guaranteed dense) or once a warp has left the loop (a
  // prefetch's claim may come after the producers left: the last worker left takes any task) and
  // while tasks wait with no production in flight (ptRole: frame 0's eye brick).
  // A frame whose backlog reaches spikeBacklog (twice what every SM producing would serve) is a
  // spike, production-bound: from then on the first PT_SPIKE_PRODUCER_EIGHTHS of the SMs
  // produce and the others render (spikeProducers), since few SMs rendering throttle the rays
  // that find its missing bricks (random-spheres forward's 267 000-brick frame: 47 ms with every
  // warp taking any work, 82 ms with every SM producing; session 40) and every warp taking any
  // work mixes the two codes on every SM (random-spheres' and fbm's slowest frames 11-16% longer
  // than split: session 64); so is a frame from an empty cache, from its start (pt_cuda.cpp:
  // spikeBacklogOf). S = 2 on an H200, 5 rounds of the 25 pt cells: FPS x1.065-1.072, 1% lows
  // x1.028-1.058, floors x0.991-0.993 (session 40); on session 44's code FPS x1.08, 1% lows
  // x1.08-1.10, the default since session 45 (BENCHMARKS.md). With S = 0, helper SMs only
  // (PT_HELPER_SMS).
  __device__ bool helpsFirst() const {
    return role == PtRole::Producer || (role == PtRole::Any && smId() % PT_HELPER_SMS == 0);
  }
  __device__ bool renders() const { return role != PtRole::Producer; }
  __device__ bool takesTasks() const {
    return role != PtRole::LeavesTasks || backoff == PT_LONGEST_SLEEP;
  }
  // Lane 0's: the warp's role this round (ptRole); the first warp to see a spike marks it.
  __device__ PtRole roleNow() const {
    if (ctx.producerShare == 0) return PtRole::Any;
    const bool spike = loadRelaxed32(ctx.counter(PT_SPIKE)) != 0;
    uint32_t ready = 0, inFlight = 0;
    if (!spike) {
      ready = loadRelaxed32(ctx.tasks.ready);
      inFlight = loadRelaxed32(ctx.counter(PT_IN_FLIGHT));
      if (ready + inFlight >= ctx.spikeBacklog) atomicExch(ctx.counter(PT_SPIKE), 1u);
    }
    return ptRole(ctx.producerShare, ctx.spikeBacklog, ctx.spikeProducers, spike, ready, inFlight,
                  smId(), loadRelaxed32(ctx.counter(PT_EXITED)) != 0);
  }
  // The samples of `owner`'s production; then, the warp's own, its end.
  __device__ void help(uint32_t owner) {
    begin(TaskKind::Produce);
    const bool own = owner == workerOf(warp());  // warp-uniform
    uint32_t id = PT_NO_TASK;
    bool chunks = true;
    if (own) {
      id = fromLane0([&] { return shared.ownTask; });
      chunks = fromLane0([&] { return shared.ownChunks ? 1u : 0u; }) != 0;
    }
    const uint32_t computed =
        !own || chunks ? produceChunks(producer, ctx.productions, owner, lane) : 0u;
    if (own) {
      if (lane == 0) shared.ownTask = PT_NO_TASK;
      closeProductionTask(ctx, pool, producer, id, chunks, warp(), lane);
    }
    worked(own || computed != 0);  // (not: every chunk was claimed before it came)
  }
  __device__ uint32_t claimPrefetch() const {
    return fromLane0([&] { return claimPrefetchItems(ctx); });
  }
  // Forced inline (as ptWorkerLoop): left to ptxas, a larger march than today's once made it a
  // call of 164 registers from the 80-register kernel, a build error (BENCHMARKS.md, session 13).
  __device__ __forceinline__ void prefetch(uint32_t first) {
    begin(TaskKind::Prefetch);
    uint32_t item = first + static_cast<uint32_t>(lane);
    const uint32_t entered = item < ctx.prefetchItems ? prefetchRay(ctx, pool, item) : 0u;
    const uint32_t sum = __reduce_add_sync(0xffffffffu, entered);
    if (lane == 0 && sum != 0) atomicAdd32(ctx.counter(PT_PREFETCH_ENTERED), sum);
    worked();
  }
  __device__ void idle() {
    if (timed()) shared.span.close(ctx.frame.timeline);
    __nanosleep(backoff);
    backoff = backoff < PT_LONGEST_SLEEP ? backoff * 2 : backoff;
  }
  __device__ void finish() {
    if (timed()) shared.span.close(ctx.frame.timeline);
  }

  // A round that found work: the warp polls again at once. One that did none (`done` false: a
  // helper that found every chunk claimed) is a poll, not work, on the timeline.
  __device__ void worked(bool done = true) {
    if (timed()) {
      if (done)
        shared.span.taskDone();
      else
        shared.span.nothingDone(ctx.frame.timeline);
    }
    backoff = PT_SHORTEST_SLEEP;
  }
  __device__ void begin(TaskKind k) {
    if (timed()) shared.span.begin(ctx.frame.timeline, k);
  }
  __device__ bool timed() const { return lane == 0 && ctx.frame.timeline.enabled(); }
  __device__ int warp() const { return static_cast<int>(threadIdx.x >> 5); }
};

template <class P>
__global__ void __launch_bounds__(PT_BLOCK, PT_MIN_BLOCKS)
    ptWorkerKernel(const __grid_constant__ PtContext ctx, const __grid_constant__ BrickPool pool,
                   const __grid_constant__ P producer) {
  awaitPriorGrids();  // the frame's start (launchDependent); the worker releases no kernel early
  __shared__ WarpWorkerShared shared[PT_WARPS];
  int lane = static_cast<int>(threadIdx.x & 31);
  WarpWorkerShared& mine = shared[threadIdx.x >> 5];
  if (lane == 0) {  // lane 0's alone: no other lane waits for them
    mine.span.open = false;
    mine.ownTask = PT_NO_TASK;
  }
  WarpWorker<P> w{ctx, pool, producer, lane, mine};
  ptWorkerLoop(ctx, w);
  if (lane == 0 && ctx.producerShare != 0) atomicAdd(ctx.counter(PT_EXITED), 1u);  // (roleNow)
}

template <class P>
int ptWorkerBlocksOf() {
  return residentBlocks(ptWorkerKernel<P>, PT_BLOCK);
}

template <class P>
void launchPtWorkers(const PtContext& ctx, const BrickPool& pool, const P& producer, int blocks,
                     cudaStream_t stream) {
  launchDependent(ptWorkerKernel<P>, blocks, PT_BLOCK, stream, ctx, pool, producer);
}

}  // namespace gvdp::detail
