// The sp loop on the CUDA backend (the loop itself: sp_loop.h), shared by `sp` (the whole frame)
// and `dp` (the sweep of rays its device-side schedule left unfinished). See sp_loop_cpu.h.
#pragma once

#include "gvdp/base/cuda_util.h"
#include "gvdp/cache/brick_cache_cuda.h"
#include "gvdp/render/march.h"
#include "gvdp/sched/ray_tasks.h"
#include "gvdp/sched/scheduler.h"
#include "gvdp/sched/tile_order_cuda.h"

namespace gvdp::detail {

// Device buffers of the loop: ray payloads, two live-ray lists, the pass counters
// ([0] rays stopped in a pass, [1] unfinished at resolve, [2] rays finished with their pixel
// written) and the image; the order of the tiled first pass's tiles (sp sets it each frame;
// row-major otherwise). With raysWritePixels (sp) a ray writes its pixel as it finishes
// (ray_tasks.h: FinishedRays) and no resolve pass runs; dp, pt and graph resolve.
struct SpBuffersCuda {
  DeviceBuffer<RayState> payload;
  DeviceBuffer<uint32_t> live, next, counters{3}, image;
  TileOrder order;
  bool raysWritePixels = false;

  FinishedRays finished() {
    return raysWritePixels ? FinishedRays{image.data(), counters.data() + 2} : FinishedRays{};
  }

  void resize(size_t pixels) {
    if (payload.size() == pixels) return;
    payload = DeviceBuffer<RayState>(pixels);
    live = DeviceBuffer<uint32_t>(pixels);
    next = DeviceBuffer<uint32_t>(pixels);
    image = DeviceBuffer<uint32_t>(pixels);
  }
  size_t bytes() const { return payload.bytes() + live.bytes() + next.bytes() + image.bytes(); }
};

// With `tiled`, the first pass starts every pixel afresh in 8x8 tiles; otherwise it resumes the
// `liveCount` rays listed in b.live. Queued bricks are produced first. Adds to stats.passes.
// Everything runs on `stream`.
void runSpLoopCuda(const FrameSetup& f, const CudaProducerKernels& producer, BrickCacheCuda& cache,
                   SpBuffersCuda& b, uint32_t liveCount, bool tiled, FrameStats& stats,
                   cudaStream_t stream);

// The frame of every cached CUDA scheduler around the sp loop's buffers (sp, graph; dp and pt
// add their own): the brick cache and the buffers sized before the clock; the image downloaded,
// the unfinished pixels counted and the cache's statistics reported after it, so that no host
// round trip ends the frame's clock. Derived schedulers write renderFrame.
class SpFrameCuda : public Scheduler {
 public:
  SpFrameCuda(const SchedulerOptions& o, ProducerKernelsPtr producer)
      : Scheduler(Backend::Cuda, std::move(producer)), cache_(poolBricksOf(o), stream()) {
    cache_.setBudget(budgetNsOf(o));
  }
  MemoryReport memory() const override;
  const uint32_t* deviceImage() const override { return buffers_.image.data(); }

 protected:
  void prepareFrame(const FrameSetup& f) override;
  void finishFrame(const FrameSetup& f, Image& out, FrameStats& stats) override;

  BrickCacheCuda cache_;
  SpBuffersCuda buffers_;
  TileOrderCuda tileOrder_;  // sp's and pt's
};

// Resolves b.payload to b.image; the unfinished pixels are counted in b.counters[1] (read after
// the frame's clock: SpFrameCuda::finishFrame).
void resolveCuda(const FrameSetup& f, SpBuffersCuda& b, cudaStream_t stream);
void downloadImage(const FrameSetup& f, const SpBuffersCuda& b, Image& out, cudaStream_t stream);

}  // namespace gvdp::detail
