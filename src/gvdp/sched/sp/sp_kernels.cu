// CUDA kernels of the sp scheduler: render passes (Algorithm 1 over the tiled screen, then over
// the compacted list of stopped rays) and resolve. Production depends on the producer:
// sp_produce.cuh.
#include "gvdp/profile/parallel_for.cuh"
#include "gvdp/profile/timeline_device.cuh"
#include "gvdp/sched/compaction.cuh"
#include "gvdp/sched/ray_tasks_warp.cuh"
#include "gvdp/sched/sp/sp_cuda.h"

namespace gvdp::detail {
namespace {

__global__ void __launch_bounds__(RENDER_BLOCK, RENDER_BLOCKS_PER_SM)
    firstRenderPassKernel(FrameSetup f, CacheView cache, BrickPool pool, TileOrder order,
                          RayState* payload, FinishedRays finished, uint32_t* next,
                          uint32_t* passCounters) {
  __shared__ WarpMarchShared shared[RENDER_BLOCK_WARPS];
  BlockTimer timer(f.timeline, TaskKind::Render);
  uint32_t start = smCycles();
  int item = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  int pixel = orderedPixel(f, order, item);
  bool stopped = renderRay(f, cache, pool, payload, pixel, true, finished,
                           WarpRays{&shared[threadIdx.x / WARP_SIZE]});
  if (threadIdx.x % WARP_SIZE == 0) noteBlockCost(order, item, smCycles() - start);
  appendStopped(stopped, static_cast<uint32_t>(pixel), next, &passCounters[0]);
}

__global__ void __launch_bounds__(RENDER_BLOCK, RENDER_BLOCKS_PER_SM)
    renderPassKernel(FrameSetup f, CacheView cache, BrickPool pool, RayState* payload,
                     FinishedRays finished, const uint32_t* live, uint32_t liveCount,
                     uint32_t* next, uint32_t* passCounters) {
  __shared__ WarpMarchShared shared[RENDER_BLOCK_WARPS];
  BlockTimer timer(f.timeline, TaskKind::Render);
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  uint32_t pixel = i < liveCount ? live[i] : 0u;
  bool stopped = renderRay(f, cache, pool, payload, i < liveCount ? static_cast<int>(pixel) : -1,
                           false, finished, WarpRays{&shared[threadIdx.x / WARP_SIZE]});
  appendStopped(stopped, pixel, next, &passCounters[0]);
}

__global__ void compactUnfinishedKernel(FrameSetup f, const RayState* payload, uint32_t* live,
                                        uint32_t* passCounters) {
  BlockTimer timer(f.timeline, TaskKind::Sweep);
  int pixel = static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x);
  bool unfinished = pixel < f.pixelCount() && !payload[pixel].finished(f.lod);
  appendStopped(unfinished, static_cast<uint32_t>(pixel), live, &passCounters[0]);
}

}  // namespace

void launchFirstRenderPass(const FrameSetup& f, const CacheView& cache, const BrickPool& pool,
                           const TileOrder& order, RayState* payload, FinishedRays finished,
                           uint32_t* next, uint32_t* passCounters, cudaStream_t stream) {
  unsigned items = static_cast<unsigned>(orderedItemCount(f));
  firstRenderPassKernel<<<(items + RENDER_BLOCK - 1) / RENDER_BLOCK, RENDER_BLOCK, 0, stream>>>(
      f, cache, pool, order, payload, finished, next, passCounters);
}

void launchRenderPass(const FrameSetup& f, const CacheView& cache, const BrickPool& pool,
                      RayState* payload, FinishedRays finished, const uint32_t* live,
                      uint32_t liveCount, uint32_t* next, uint32_t* passCounters,
                      cudaStream_t stream) {
  renderPassKernel<<<(liveCount + RENDER_BLOCK - 1) / RENDER_BLOCK, RENDER_BLOCK, 0, stream>>>(
      f, cache, pool, payload, finished, live, liveCount, next, passCounters);
}

void launchCompactUnfinished(const FrameSetup& f, const RayState* payload, uint32_t* live,
                             uint32_t* passCounters, cudaStream_t stream) {
  unsigned n = static_cast<unsigned>(f.pixelCount());
  compactUnfinishedKernel<<<(n + 255) / 256, 256, 0, stream>>>(f, payload, live, passCounters);
}

void launchResolve(const FrameSetup& f, const RayState* payload, uint32_t* image,
                   uint32_t* passCounters, cudaStream_t stream) {
  parallelForCuda("resolve", stream, static_cast<uint32_t>(f.pixelCount()), f.timeline,
                  TaskKind::Resolve, [=] __device__(uint32_t pixel) {
                    bool unfinished = false;
                    image[pixel] = resolveRay(f, payload, static_cast<int>(pixel), &unfinished);
                    if (unfinished) atomicAdd(&passCounters[1], 1u);
                  });
}

}  // namespace gvdp::detail
