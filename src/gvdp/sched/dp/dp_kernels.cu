// CUDA kernels of the dp scheduler: render tasks and production tasks that launch each other
// with CUDA Dynamic Parallelism (CDP2, fire-and-forget streams), as in paper 3.3.
#include "gvdp/profile/timeline_device.cuh"
#include "gvdp/sched/dp/dp_cuda.h"
#include "gvdp/sched/produce_block.cuh"

namespace gvdp {

__device__ DpContext dpContext;  // the frame's context, read by every task (launches stay small)
__device__ BrickPool dpPool;

constexpr int DP_RELAUNCH_BLOCK = 16;

__global__ void dpProduceKernel(BrickKey key, int depth);
__global__ void dpRenderRectKernel(PixelRect rect, int depth);

struct GpuLauncher {
  int depth;  // of the grid this thread runs in

  __device__ void produce(const BrickKey& key, uint32_t* entry) const {
    const DpContext& ctx = dpContext;
    if (depth + 1 > DP_MAX_DEPTH) {
      requestBrick(ctx.cache, key.level, key.brick);
      atomicAdd(&ctx.counters[DP_DEFERRED], 1u);
      return;
    }
    dpProduceKernel<<<1, PRODUCE_BLOCK, 0, cudaStreamFireAndForget>>>(key, depth + 1);
    if (cudaGetLastError() == cudaSuccess) {
      atomicAdd(&ctx.counters[DP_PRODUCTIONS], 1u);
    } else {  // refused: the brick is MISSING again; its rays are left to the sweep
      storeRelease32(entry, ENTRY_MISSING);
      atomicAdd(&ctx.counters[DP_LAUNCH_FAILURES], 1u);
    }
  }

  __device__ void relaunch(const PixelRect& r) const {
    const DpContext& ctx = dpContext;
    if (r.width() <= 0 || r.height() <= 0) return;
    if (depth + 1 > DP_MAX_DEPTH) {
      atomicAdd(&ctx.counters[DP_DEFERRED], 1u);
      return;
    }
    dim3 block(DP_RELAUNCH_BLOCK, DP_RELAUNCH_BLOCK);
    dim3 grid((r.width() + DP_RELAUNCH_BLOCK - 1) / DP_RELAUNCH_BLOCK,
              (r.height() + DP_RELAUNCH_BLOCK - 1) / DP_RELAUNCH_BLOCK);
    dpRenderRectKernel<<<grid, block, 0, cudaStreamFireAndForget>>>(r, depth + 1);
    if (cudaGetLastError() == cudaSuccess)
      atomicAdd(&ctx.counters[DP_RELAUNCHES], 1u);
    else
      atomicAdd(&ctx.counters[DP_LAUNCH_FAILURES], 1u);
  }
};

__global__ void __launch_bounds__(PRODUCE_BLOCK) dpProduceKernel(BrickKey key, int depth) {
  BlockTimer timer(TaskKind::Produce);
  const DpContext& ctx = dpContext;
  produceBrickBlock(ctx.frame.scene, ctx.cache, dpPool, key);
  if (threadIdx.x == 0)
    GpuLauncher{depth}.relaunch(brickScreenRect(ctx.frame, ctx.cache.clipmap, key));
}

__global__ void dpRenderRectKernel(PixelRect rect, int depth) {
  BlockTimer timer(TaskKind::Render);
  int x = rect.x0 + static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  int y = rect.y0 + static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= rect.x1 || y >= rect.y1) return;
  GpuLauncher launcher{depth};
  dpRenderPixel(dpContext, dpPool, launcher, y * dpContext.frame.width + x);
}

__global__ void __launch_bounds__(DP_TILE_W* DP_TILE_H) dpRootKernel() {
  BlockTimer timer(TaskKind::Render);
  const DpContext& ctx = dpContext;
  int pixel = dpTilePixel(ctx.frame, static_cast<int>(blockIdx.x), static_cast<int>(threadIdx.x));
  if (pixel < 0) return;
  GpuLauncher launcher{0};
  dpRenderPixel(ctx, dpPool, launcher, pixel);
}

void launchDpFrame(const DpContext& ctx, const BrickPool& pool) {
  cudaMemcpyToSymbol(dpContext, &ctx, sizeof ctx);
  cudaMemcpyToSymbol(dpPool, &pool, sizeof pool);
  dpRootKernel<<<dpTileCount(ctx.frame), DP_TILE_W * DP_TILE_H>>>();
}

}  // namespace gvdp
