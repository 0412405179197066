#include "gvdp/sched/sp/sp_cuda.h"
#include "gvdp/sched/producer_kernels_cuda.h"
#include "gvdp/sched/sp/sp.h"
#include "gvdp/sched/sp/sp_loop_cuda.h"

namespace gvdp {

namespace {
void produceQueued(const FrameSetup& f, const CudaProducerKernels& producer,
                   BrickCacheCuda& cache) {
  NvtxRange range("production pass");
  uint32_t before[COUNTER_COUNT], after[COUNTER_COUNT];
  cache.readCounters(before);
  uint32_t requests = std::min(before[COUNTER_REQUESTS], cache.view().requestCapacity);
  if (requests == 0) return;
  producer.launchProduce(f, cache.view(), cache.pool(), requests);
  cache.clearRequests();
  cache.readCounters(after);
  if (after[COUNTER_FAILED] != before[COUNTER_FAILED] && cache.refill() == 0)
    cache.setDegraded(true);
}
}  // namespace

void runSpLoopCuda(const FrameSetup& f, const CudaProducerKernels& producer, BrickCacheCuda& cache,
                   SpBuffersCuda& b, uint32_t liveCount, bool tiled, FrameStats& stats) {
  produceQueued(f, producer, cache);
  for (int pass = 0;; ++pass) {
    NvtxRange range("render pass");
    GVDP_CUDA_CHECK(cudaMemset(b.counters.data(), 0, 4));
    if (pass == 0 && tiled) {
      launchFirstRenderPass(f, cache.view(), cache.pool(), b.payload.data(), b.next.data(),
                            b.counters.data());
    } else {
      launchRenderPass(f, cache.view(), cache.pool(), b.payload.data(), b.live.data(), liveCount,
                       b.next.data(), b.counters.data());
    }
    GVDP_CUDA_CHECK(cudaGetLastError());
    ++stats.passes;
    std::swap(b.live, b.next);
    // The GigaVoxels loop: the host reads the counts after every pass.
    GVDP_CUDA_CHECK(cudaMemcpy(&liveCount, b.counters.data(), 4, cudaMemcpyDeviceToHost));
    if (liveCount == 0) return;
    produceQueued(f, producer, cache);
    if (stats.passes >= SP_MAX_PASSES) cache.setDegraded(true);
  }
}

int64_t resolveCuda(const FrameSetup& f, SpBuffersCuda& b) {
  GVDP_CUDA_CHECK(cudaMemset(b.counters.data() + 1, 0, 4));
  launchResolve(f, b.payload.data(), b.image.data(), b.counters.data());
  GVDP_CUDA_CHECK(cudaGetLastError());
  uint32_t unfinished = 0;
  GVDP_CUDA_CHECK(cudaMemcpy(&unfinished, b.counters.data() + 1, 4, cudaMemcpyDeviceToHost));
  return unfinished;
}

void downloadImage(const FrameSetup& f, const SpBuffersCuda& b, Image& out) {
  out = Image(f.width, f.height);
  GVDP_CUDA_CHECK(
      cudaMemcpy(out.pixels.data(), b.image.data(), b.image.bytes(), cudaMemcpyDeviceToHost));
}

MemoryReport SpFrameCuda::memory() const {
  MemoryReport m = cache_.memory();
  m.push_back({"ray_payload_lists_image", buffers_.bytes()});
  return m;
}

void SpFrameCuda::prepareFrame(const FrameSetup& f) {
  buffers_.resize(static_cast<size_t>(f.pixelCount()));
}

void SpFrameCuda::finishFrame(const FrameSetup& f, Image& out, FrameStats& stats) {
  if (hostImageWanted()) downloadImage(f, buffers_, out);
  addCacheStats(cache_, stats);
}

namespace {

class SpCuda final : public SpFrameCuda {
 public:
  SpCuda(const SchedulerOptions& o, ProducerKernelsPtr p) : SpFrameCuda(o, std::move(p)) {}

 private:
  void renderFrame(const FrameSetup& f, Image&, FrameStats& stats) override {
    NvtxRange range("sp frame");
    cache_.beginFrame(f);
    runSpLoopCuda(f, cudaProducer(), cache_, buffers_, 0, true, stats);
    stats.unfinishedPixels = resolveCuda(f, buffers_);
  }
};

}  // namespace

std::unique_ptr<Scheduler> makeSpCuda(const SchedulerOptions& o, ProducerKernelsPtr producer) {
  return std::make_unique<SpCuda>(o, std::move(producer));
}

}  // namespace gvdp
