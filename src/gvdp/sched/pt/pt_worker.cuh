// The persistent kernel of the pt scheduler: every warp is a worker of pt's loop (pt_body.h) that
// takes a production task (the warp produces the brick: 1000 samples over 32 lanes), up to 32
// relaunched rays, or the next 8x4 pixels of the screen, until no ray or task of the frame is left.
// Timeline records are per warp: a span of consecutive tasks of one kind, closed when the warp
// switches kind or finds no work (idle warps are idle on the timeline). A template on the
// producer (producer_kernels_of.h); the rings' initialisation is in pt_kernels.cu.
#pragma once

#include "gvdp/base/cuda_util.h"
#include "gvdp/cache/produce.h"
#include "gvdp/profile/timeline_device.cuh"
#include "gvdp/render/brick_pool.h"
#include "gvdp/sched/pt/pt_body.h"

namespace gvdp::detail {

// 3 blocks of 8 warps per SM (80 registers): measured on an H100 against 2 (125 registers) and
// 4 (64, spilling), perlin 1500x1000: 24 ms per frame against 39 and 25.
constexpr int PT_BLOCK = 256, PT_WARPS = PT_BLOCK / 32, PT_MIN_BLOCKS = 3;
constexpr unsigned FULL_MASK = 0xffffffffu;

// Lane 0's open timeline span.
struct WarpSpan {
  TimelineView timeline;
  bool on, open = false;
  TaskKind kind = TaskKind::Render;
  uint64_t start = 0, end = 0;

  __device__ void begin(TaskKind k) {
    if (!on) return;
    if (open && k == kind) return;
    close();
    kind = k;
    start = clockNanoseconds();
    open = true;
  }
  __device__ void taskDone() {
    if (on) end = clockNanoseconds();
  }
  __device__ void close() {
    if (!on || !open) return;
    uint16_t sm = static_cast<uint16_t>(smId());
    timeline.push({start, end, sm, sm, kind});
    open = false;
  }
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
    int lane = static_cast<int>(threadIdx.x & 31), leader = __ffs(static_cast<int>(group)) - 1;
    unsigned above = group & ~((2u << lane) - 1u);
    uint32_t next = __shfl_sync(group, pixel, above ? __ffs(static_cast<int>(above)) - 1 : lane);
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
    return static_cast<int>(threadIdx.x & 31) == __ffs(static_cast<int>(group)) - 1;
  }
};

__device__ inline void renderLanes(const PtContext& ctx, const BrickPool& pool, int pixel,
                                   bool relaunched, int lane) {
  bool finished =
      pixel >= 0 && ptRunRay(ctx, pool, static_cast<uint32_t>(pixel), relaunched, ParkWarp{});
  unsigned done = __ballot_sync(FULL_MASK, finished);
  if (lane == 0) {
    if (done) atomicSub(ctx.counter(PT_LIVE_WORK), static_cast<uint32_t>(__popc(done)));
    atomicAdd(ctx.counter(PT_RENDER_TASKS), 1u);
  }
}

// Productions in flight in a block, whose chunks (4 samples per lane) any warp of the block may
// compute: the owner warp computes chunks until none is left, then waits for its helpers. Only
// warps with nothing else to take help (helping before rendering halved production throughput,
// measured); in the frame's tail, a chain of dependent productions, they cut latency up to 8x.
//
// Warps hand these words to each other without a block barrier (the set of helpers is not known
// in advance), so every access to them is a strong one: writes are atomic exchanges or
// read-modify-writes, reads are volatile (relaxed) loads. The PTX memory model then sees no data
// race, and the release/acquire pairs below order the data: the owner publishes key and counters
// (fence, then `next`), a helper acquires them by claiming a chunk (atomic on `next`, then
// fence); a helper publishes its samples (fence, then `done`), the owner acquires them by
// reading `done` (then fence). compute-sanitizer's racecheck, which orders accesses only through
// barriers and atomics, agrees: plain stores here were its 5 hazards (stage and key).
constexpr int PRODUCE_CHUNK = 128, PRODUCE_CHUNKS = (BRICK_SAMPLE_COUNT + 127) / 128;

struct BlockProductions {
  Rgba8 stage[PT_WARPS][BRICK_SAMPLE_COUNT];
  BrickKey key[PT_WARPS];
  uint32_t next[PT_WARPS];      // next chunk to claim (runs past PRODUCE_CHUNKS)
  uint32_t done[PT_WARPS];      // chunks computed
  uint32_t nonEmpty[PT_WARPS];  // nonzero once a chunk found a non-empty sample
  uint32_t open;                // bit w: warp w's production has chunks to claim
};

// A strong store of a word that other warps of the block read without a barrier.
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

// Claims and computes chunks of warp `owner`'s production until none is left.
template <class P>
__device__ void produceChunks(const P& producer, BlockProductions& bp, int owner, int lane) {
  for (;;) {
    uint32_t c = 0;
    if (lane == 0) {
      c = atomicAdd(&bp.next[owner], 1u);
      __threadfence_block();  // acquire: the key the owner wrote before opening the production
    }
    c = __shfl_sync(FULL_MASK, c, 0);
    if (c >= static_cast<uint32_t>(PRODUCE_CHUNKS)) return;
    // The last chunk is taken: no more help (helpers would spin on an exhausted production).
    if (lane == 0 && c == PRODUCE_CHUNKS - 1) atomicAnd(&bp.open, ~(1u << owner));
    __syncwarp();  // lane 0's acquire before every lane's read of the key
    BrickKey key = loadBrickKey(&bp.key[owner]);
    bool bounded = brickBoundedEmpty(producer, key);  // the producer's box bound: no samples
    bool nonEmpty = false;
    int end = min((static_cast<int>(c) + 1) * PRODUCE_CHUNK, BRICK_SAMPLE_COUNT);
    for (int s = static_cast<int>(c) * PRODUCE_CHUNK + lane; s < end; s += 32) {
      VoxelSample v = bounded ? VoxelSample{0u, true} : produceBrickSample(producer, key, s);
      handOver(&bp.stage[owner][s], v.rgba);
      nonEmpty = nonEmpty || !v.empty;
    }
    nonEmpty = __any_sync(FULL_MASK, nonEmpty);
    __syncwarp();  // every lane's samples before lane 0's release
    if (lane == 0) {
      if (nonEmpty) atomicOr(&bp.nonEmpty[owner], 1u);
      __threadfence_block();  // release: the samples and nonEmpty before `done`
      atomicAdd(&bp.done[owner], 1u);
    }
  }
}

// Algorithm 2 by warp `warp` (helped by idle warps of its block), then the task's waiting rays
// queued again as full warps.
template <class P>
__device__ void produceTask(const PtContext& ctx, const BrickPool& pool, const P& producer,
                            uint32_t id, BlockProductions& bp, int warp, int lane) {
  BrickKey key = loadTaskKey(ctx, id);
  if (lane == 0) {  // no helper is in this production's words: the last one counted its chunk
    handOverKey(&bp.key[warp], key);
    handOver(&bp.nonEmpty[warp], 0u);
    handOver(&bp.done[warp], 0u);
    __threadfence_block();  // release: key and counters before the first claim
    atomicExch(&bp.next[warp], 0u);
    __threadfence_block();
    atomicOr(&bp.open, 1u << warp);
  }
  __syncwarp();
  produceChunks(producer, bp, warp, lane);
  if (lane == 0) {
    while (loadRelaxed32(&bp.done[warp]) < static_cast<uint32_t>(PRODUCE_CHUNKS)) __nanosleep(20);
    __threadfence_block();  // acquire: every helper's samples
  }
  __syncwarp();
  bool empty = loadRelaxed32(&bp.nonEmpty[warp]) == 0;
  const Rgba8* stage = bp.stage[warp];
  constexpr int PER = (BRICK_SAMPLE_COUNT + 31) / 32;
  commitBrick<PER>(WarpScope{lane}, producer, ctx.cache, pool, key, empty,
                   [&](int, int s) { return loadRelaxed32(&stage[s]); });
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
  if (lane == 0) {
    atomicAdd(ctx.counter(PT_RELAUNCHED), relaunched);
    atomicAdd(ctx.counter(PT_PRODUCTIONS), 1u);
    endTask(ctx, id);
  }
}

// One worker (a warp) of pt's loop (pt_body.h): every lane runs every step, lane 0 claims and
// shares what it claimed. With nothing to take, the warp helps a production of its block (the
// tail of the frame), or sleeps with an exponential backoff.
template <class P>
struct WarpWorker {
  const PtContext& ctx;
  const BrickPool& pool;
  const P& producer;
  BlockProductions& bp;
  int warp, lane;
  WarpSpan span;
  unsigned backoff = 32;

  __device__ uint32_t liveWork() const {
    uint32_t live = 0;
    if (lane == 0) live = loadRelaxed32(ctx.counter(PT_LIVE_WORK));
    return __shfl_sync(FULL_MASK, live, 0);
  }
  __device__ uint32_t claim(const Ring& r, uint32_t n, uint32_t* position) const {
    return warpClaim(r, n, position, lane);
  }
  __device__ void produce(uint32_t position) {
    span.begin(TaskKind::Produce);
    uint32_t id = 0;
    if (lane == 0) id = ringTake(ctx.tasks, position);
    produceTask(ctx, pool, producer, __shfl_sync(FULL_MASK, id, 0), bp, warp, lane);
    worked();
  }
  __device__ void renderQueued(uint32_t position, uint32_t n) {
    span.begin(TaskKind::Render);
    int pixel =
        lane < static_cast<int>(n) ? static_cast<int>(ringTake(ctx.rays, position + lane)) : -1;
    renderLanes(ctx, pool, pixel, true, lane);
    worked();
  }
  __device__ uint32_t claimFresh() const {
    uint32_t first = 0;
    if (lane == 0) first = claimFreshItems(ctx);
    return __shfl_sync(FULL_MASK, first, 0);
  }
  __device__ void renderFresh(uint32_t first) {
    span.begin(TaskKind::Render);
    uint32_t item = first + static_cast<uint32_t>(lane);
    renderLanes(ctx, pool,
                item < ctx.itemCount ? tiledPixel(ctx.frame, static_cast<int>(item)) : -1, false,
                lane);
    worked();
  }
  __device__ void idle() {
    uint32_t open = 0;
    if (lane == 0) open = loadRelaxed32(&bp.open) & ~(1u << warp);
    open = __shfl_sync(FULL_MASK, open, 0);
    if (open) {
      span.begin(TaskKind::Produce);
      produceChunks(producer, bp, __ffs(static_cast<int>(open)) - 1, lane);
      worked();
      return;
    }
    span.close();
    __nanosleep(backoff);
    backoff = backoff < 1024 ? backoff * 2 : backoff;
  }
  __device__ void finish() { span.close(); }

  __device__ void worked() {
    span.taskDone();
    backoff = 32;
  }
};

template <class P>
__global__ void __launch_bounds__(PT_BLOCK, PT_MIN_BLOCKS)
    ptWorkerKernel(const __grid_constant__ PtContext ctx, const __grid_constant__ BrickPool pool,
                   const __grid_constant__ P producer) {
  __shared__ BlockProductions bp;
  int lane = static_cast<int>(threadIdx.x & 31), warp = static_cast<int>(threadIdx.x >> 5);
  if (threadIdx.x == 0) bp.open = 0;
  if (lane == 0) bp.next[warp] = PRODUCE_CHUNKS;
  __syncthreads();
  WarpWorker<P> w{ctx,
                  pool,
                  producer,
                  bp,
                  warp,
                  lane,
                  WarpSpan{ctx.frame.timeline, lane == 0 && ctx.frame.timeline.enabled()}};
  ptWorkerLoop(ctx, w);
}

template <class P>
int ptWorkerBlocksOf() {
  return residentBlocks(ptWorkerKernel<P>, PT_BLOCK);
}

template <class P>
void launchPtWorkers(const PtContext& ctx, const BrickPool& pool, const P& producer, int blocks,
                     cudaStream_t stream) {
  ptWorkerKernel<<<blocks, PT_BLOCK, 0, stream>>>(ctx, pool, producer);
}

}  // namespace gvdp::detail
