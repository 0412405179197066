// CUDA kernels of the dp scheduler: render tasks and production tasks that launch each other
// with CUDA Dynamic Parallelism (CDP2, fire-and-forget streams), as in paper 3.3. Every task
// gets the frame's context in device memory (a pointer, so launches stay small and no device
// global is shared between renderers); render tasks read it from a copy in shared memory
// (block_copy.cuh), and pass the global pointer on to the tasks they launch. Device-side launches
// need relocatable device code: instantiate these only where __CUDACC_RDC__ is defined
// (producer_kernels_of.h).
#pragma once

#include "gvdp/profile/timeline_device.cuh"
#include "gvdp/sched/block_copy.cuh"
#include "gvdp/sched/dp/dp_body.h"
#include "gvdp/sched/produce_block.cuh"

namespace gvdp::detail {

// Kernels nest at most this deep (CUDA's launch nesting limit is 24); a production that would
// go deeper is queued for the host's sweep instead (counted as DP_DEFERRED).
constexpr int DP_MAX_DEPTH = 23;
constexpr int DP_RELAUNCH_BLOCK = 16;

// The device runtime's pending-launch buffer is never let fill: a frame's device launches are
// at most its allowance (DpContext::launchAllowance, half the buffer; the host waits for the
// whole tree before the next frame, so no launch of an earlier frame is pending). A launch past
// it is refused as one the runtime refuses: counted, its rays left to the sweep.
__device__ inline bool reserveLaunch(const DpContext* ctx) {
  return atomicAdd(&ctx->counters[DP_RESERVED], 1u) < ctx->launchAllowance;
}

// A device-side launch within the allowance: reserved, launched, checked, and counted as `counted`
// or as a launch failure; false when refused (by the allowance or by the runtime).
template <class Launch>
__device__ bool launchReserved(const DpContext* ctx, DpCounter counted, Launch launch) {
  bool launched = reserveLaunch(ctx);
  if (launched) {
    launch();
    launched = cudaGetLastError() == cudaSuccess;
  }
  atomicAdd(&ctx->counters[launched ? counted : DP_LAUNCH_FAILURES], 1u);
  return launched;
}

template <class P>
__global__ void dpProduceKernel(const DpContext* ctx, P producer, BrickKey key, int depth);
template <class P>
__global__ void dpRenderRectKernel(const DpContext* ctx, P producer, PixelRect rect, int depth);

template <class P>
struct GpuLauncher {
  const DpContext* ctx;
  const P& producer;
  int depth;  // of the grid this thread runs in

  __device__ void produce(const BrickKey& key, uint32_t* entry) const {
    if (depth + 1 > DP_MAX_DEPTH) {
      requestBrick(ctx->cache, key.level, key.brick, entry);
      atomicAdd(&ctx->counters[DP_DEFERRED], 1u);
      return;
    }
    if (!launchReserved(ctx, DP_PRODUCTIONS, [&] {
          dpProduceKernel<<<1, PRODUCE_BLOCK, 0, cudaStreamFireAndForget>>>(ctx, producer, key,
                                                                            depth + 1);
        }))
      storeRelease32(entry, ENTRY_MISSING);  // refused: MISSING again, its rays left to the sweep
  }

  __device__ void relaunch(const PixelRect& r) const {
    if (r.width() <= 0 || r.height() <= 0) return;
    if (depth + 1 > DP_MAX_DEPTH) {
      atomicAdd(&ctx->counters[DP_DEFERRED], 1u);
      return;
    }
    dim3 block(DP_RELAUNCH_BLOCK, DP_RELAUNCH_BLOCK);
    dim3 grid((r.width() + DP_RELAUNCH_BLOCK - 1) / DP_RELAUNCH_BLOCK,
              (r.height() + DP_RELAUNCH_BLOCK - 1) / DP_RELAUNCH_BLOCK);
    launchReserved(ctx, DP_RELAUNCHES, [&] {
      dpRenderRectKernel<<<grid, block, 0, cudaStreamFireAndForget>>>(ctx, producer, r, depth + 1);
    });
  }
};

template <class P>
__global__ void __launch_bounds__(PRODUCE_BLOCK)
    dpProduceKernel(const DpContext* ctx, P producer, BrickKey key, int depth) {
  BlockTimer timer(ctx->frame.timeline, TaskKind::Produce);
  produceBrickBlock(producer, ctx->cache, ctx->pool, key);
  if (threadIdx.x == 0)
    GpuLauncher<P>{ctx, producer, depth}.relaunch(
        brickScreenRect(ctx->frame, ctx->cache.clipmap, key));
}

template <class P>
__global__ void dpRenderRectKernel(const DpContext* ctx, P producer, PixelRect rect, int depth) {
  const DpContext& local = blockCopy(ctx);
  BlockTimer timer(local.frame.timeline, TaskKind::Render);
  int x = rect.x0 + static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  int y = rect.y0 + static_cast<int>(blockIdx.y * blockDim.y + threadIdx.y);
  if (x >= rect.x1 || y >= rect.y1) return;
  GpuLauncher<P> launcher{ctx, producer, depth};
  dpRenderPixel(local, local.pool, launcher, y * local.frame.width + x);
}

template <class P>
__global__ void __launch_bounds__(DP_TILE_W* DP_TILE_H)
    dpRootKernel(const DpContext* ctx, P producer) {
  const DpContext& local = blockCopy(ctx);
  BlockTimer timer(local.frame.timeline, TaskKind::Render);
  int pixel = dpTilePixel(local.frame, static_cast<int>(blockIdx.x), static_cast<int>(threadIdx.x));
  if (pixel < 0) return;
  GpuLauncher<P> launcher{ctx, producer, 0};
  dpRenderPixel(local, local.pool, launcher, pixel);
}

// The root render grid (32x16 tiles) over the context in device memory; the whole tree of
// device launches has finished when the stream reaches the next command.
template <class P>
void launchDpRoot(const DpContext* deviceContext, const FrameSetup& frame, const P& producer,
                  cudaStream_t stream) {
  dpRootKernel<<<dpTileCount(frame), DP_TILE_W * DP_TILE_H, 0, stream>>>(deviceContext, producer);
}

}  // namespace gvdp::detail
