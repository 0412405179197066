// The persistent kernel of the pt scheduler: every warp is a worker that takes, in this order, a
// production task (the warp produces the brick: 1000 samples over 32 lanes), up to 32 relaunched
// rays, or the next 8x4 pixels of the screen, until no ray of the frame is left (pt_body.h).
// Timeline records are per warp: a span of consecutive tasks of one kind, closed when the warp
// switches kind or finds no work (idle warps are idle on the timeline).
#include "gvdp/base/cuda_util.h"
#include "gvdp/profile/timeline_device.cuh"
#include "gvdp/sched/pt_cuda.h"

namespace gvdp {
namespace {

// 3 blocks of 8 warps per SM (80 registers): measured on an H100 against 2 (125 registers) and
// 4 (64, spilling), perlin 1500x1000: 24 ms per frame against 39 and 25.
constexpr int PT_BLOCK = 256, PT_WARPS = PT_BLOCK / 32, PT_MIN_BLOCKS = 3;
constexpr unsigned FULL_MASK = 0xffffffffu;

// Lane 0's open timeline span.
struct WarpSpan {
  bool on, open = false;
  TaskKind kind = TaskKind::Render;
  uint64_t start = 0, end = 0;

  __device__ void begin(TaskKind k) {
    if (!on) return;
    if (open && k == kind) return;
    close();
    kind = k;
    start = globalTimer();
    open = true;
  }
  __device__ void taskDone() {
    if (on) end = globalTimer();
  }
  __device__ void close() {
    if (!on || !open) return;
    uint16_t sm = static_cast<uint16_t>(smId());
    deviceTimeline.push({start, end, sm, sm, kind});
    open = false;
  }
};

__device__ uint32_t warpClaim(const Ring& r, uint32_t n, uint32_t* position, int lane) {
  uint32_t got = 0, pos = 0;
  if (lane == 0) got = ringClaim(r, n, &pos);
  *position = __shfl_sync(FULL_MASK, pos, 0);
  return __shfl_sync(FULL_MASK, got, 0);
}

__device__ void renderLanes(const PtContext& ctx, const BrickPool& pool, int pixel, int lane) {
  bool finished = pixel >= 0 && ptRunRay(ctx, pool, static_cast<uint32_t>(pixel));
  unsigned done = __ballot_sync(FULL_MASK, finished);
  if (lane == 0) {
    if (done) atomicSub(ctx.counter(PT_LIVE_RAYS), static_cast<uint32_t>(__popc(done)));
    atomicAdd(ctx.counter(PT_RENDER_TASKS), 1u);
  }
}

// Algorithm 2 by one warp, then the task's waiting rays queued again as full warps.
__device__ void produceTask(const PtContext& ctx, const BrickPool& pool, uint32_t id, Rgba8* stage,
                            int lane) {
  BrickKey key = loadTaskKey(ctx, id);
  bool empty = true;
  for (int s = lane; s < BRICK_SAMPLE_COUNT; s += 32) {
    VoxelSample v = produceBrickSample(ctx.frame.scene, key, s);
    stage[s] = v.rgba;
    empty = empty && v.empty;
  }
  empty = __all_sync(FULL_MASK, empty);
  uint32_t slot = 0;
  if (lane == 0) slot = empty ? MAX_SLOTS : takeFreeSlot(ctx.cache);
  slot = __shfl_sync(FULL_MASK, slot, 0);
  if (!empty && slot != MAX_SLOTS) {
    for (int s = lane; s < BRICK_SAMPLE_COUNT; s += 32) pool.write(slot, s, stage[s]);
    __threadfence();
  }
  __syncwarp();
  uint32_t p = 0;
  if (lane == 0) {
    publishBrick(ctx.cache, key, empty, slot);
    p = closeWaitList(ctx, id);
  }
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
    releaseTaskId(ctx, id);
  }
}

__global__ void __launch_bounds__(PT_BLOCK, PT_MIN_BLOCKS)
    ptWorkerKernel(const __grid_constant__ PtContext ctx, const __grid_constant__ BrickPool pool) {
  __shared__ Rgba8 stage[PT_WARPS][BRICK_SAMPLE_COUNT];
  int lane = static_cast<int>(threadIdx.x & 31), warp = static_cast<int>(threadIdx.x >> 5);
  WarpSpan span{lane == 0 && deviceTimeline.enabled()};
  unsigned backoff = 32;
  for (;;) {
    uint32_t live = 0;
    if (lane == 0) live = loadRelaxed32(ctx.counter(PT_LIVE_RAYS));
    if (__shfl_sync(FULL_MASK, live, 0) == 0) break;
    uint32_t position = 0;
    if (warpClaim(ctx.tasks, 1, &position, lane)) {
      span.begin(TaskKind::Produce);
      uint32_t id = 0;
      if (lane == 0) id = ringTake(ctx.tasks, position);
      produceTask(ctx, pool, __shfl_sync(FULL_MASK, id, 0), stage[warp], lane);
    } else if (uint32_t n = warpClaim(ctx.rays, PT_BATCH, &position, lane)) {
      span.begin(TaskKind::Render);
      int pixel =
          lane < static_cast<int>(n) ? static_cast<int>(ringTake(ctx.rays, position + lane)) : -1;
      renderLanes(ctx, pool, pixel, lane);
    } else {
      uint32_t first = ctx.itemCount;
      if (lane == 0 && loadRelaxed32(ctx.counter(PT_NEXT_ITEM)) < ctx.itemCount)
        first = atomicAdd(ctx.counter(PT_NEXT_ITEM), static_cast<uint32_t>(PT_BATCH));
      first = __shfl_sync(FULL_MASK, first, 0);
      if (first >= ctx.itemCount) {  // no work now: idle
        span.close();
        __nanosleep(backoff);
        backoff = backoff < 1024 ? backoff * 2 : backoff;
        continue;
      }
      span.begin(TaskKind::Render);
      uint32_t item = first + static_cast<uint32_t>(lane);
      renderLanes(ctx, pool,
                  item < ctx.itemCount ? tiledPixel(ctx.frame, static_cast<int>(item)) : -1, lane);
    }
    span.taskDone();
    backoff = 32;
  }
  span.close();
}

__global__ void ringInitKernel(Ring ring, uint32_t filled) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i <= ring.mask) ring.slots[i] = ringInitialSlot(i, filled);
}

void initRing(const Ring& ring, uint32_t filled) {
  uint32_t n = ring.mask + 1;
  ringInitKernel<<<(n + 255) / 256, 256>>>(ring, filled);
}

}  // namespace

int ptWorkerBlocks() {
  int device = 0, sms = 0, perSm = 0;
  GVDP_CUDA_CHECK(cudaGetDevice(&device));
  GVDP_CUDA_CHECK(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, device));
  GVDP_CUDA_CHECK(
      cudaOccupancyMaxActiveBlocksPerMultiprocessor(&perSm, ptWorkerKernel, PT_BLOCK, 0));
  return sms * (perSm > 0 ? perSm : 1);
}

void launchPtRingsInit(const PtContext& ctx, uint32_t ids) {
  initRing(ctx.rays, 0);
  initRing(ctx.tasks, 0);
  initRing(ctx.freeIds, ids);
}

void launchPtFrame(const PtContext& ctx, const BrickPool& pool, int blocks) {
  ptWorkerKernel<<<blocks, PT_BLOCK>>>(ctx, pool);
}

}  // namespace gvdp
