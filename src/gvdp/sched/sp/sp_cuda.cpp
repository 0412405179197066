#include "gvdp/sched/sp/sp_cuda.h"
#include "gvdp/sched/producer_kernels_cuda.h"
#include "gvdp/sched/sp/sp.h"
#include "gvdp/sched/sp/sp_loop.h"
#include "gvdp/sched/sp/sp_loop_cuda.h"

namespace gvdp::detail {

namespace {
// The sp loop's steps on the CUDA backend (sp_loop.h): the host reads the counts after every
// pass, as GigaVoxels does.
struct SpStepsCuda {
  const FrameSetup& f;
  const CudaProducerKernels& producer;
  BrickCacheCuda& cache_;
  SpBuffersCuda& b;
  cudaStream_t stream;

  BrickCacheCuda& cache() { return cache_; }

  void produce(uint32_t requests) {
    NvtxRange range("production pass");
    producer.launchProduce(f, cache_.view(), cache_.pool(), requests, stream);
  }

  uint32_t renderPass(bool tiled, uint32_t liveCount) {
    NvtxRange range("render pass");
    // The frame's first pass zeroes its finished rays too.
    fillDevice(b.counters.data(), 0, (tiled ? 3 : 1) * sizeof(uint32_t), stream);
    if (tiled) {
      launchFirstRenderPass(f, cache_.view(), cache_.pool(), b.order, b.payload.data(),
                            b.finished(), b.next.data(), b.counters.data(), stream);
    } else {
      launchRenderPass(f, cache_.view(), cache_.pool(), b.payload.data(), b.finished(),
                       b.live.data(), liveCount, b.next.data(), b.counters.data(), stream);
    }
    GVDP_CUDA_CHECK(cudaGetLastError());
    std::swap(b.live, b.next);
    uint32_t stopped = 0;
    readDevice(&stopped, b.counters.data(), 4, stream);
    return stopped;
  }
};
}  // namespace

void runSpLoopCuda(const FrameSetup& f, const CudaProducerKernels& producer, BrickCacheCuda& cache,
                   SpBuffersCuda& b, uint32_t liveCount, bool tiled, FrameStats& stats,
                   cudaStream_t stream) {
  SpStepsCuda steps{f, producer, cache, b, stream};
  runSpLoop(steps, liveCount, tiled, stats);
}

void resolveCuda(const FrameSetup& f, SpBuffersCuda& b, cudaStream_t stream) {
  fillDevice(b.counters.data() + 1, 0, 4, stream);
  launchResolve(f, b.payload.data(), b.image.data(), b.counters.data(), stream);
  GVDP_CUDA_CHECK(cudaGetLastError());
}

void downloadImage(const FrameSetup& f, const SpBuffersCuda& b, Image& out, cudaStream_t stream) {
  out = Image(f.width, f.height);
  readDevice(out.pixels.data(), b.image.data(), b.image.bytes(), stream);
}

MemoryReport SpFrameCuda::memory() const {
  MemoryReport m = cache_.memory();
  m.push_back({"ray_payload_lists_image", buffers_.bytes()});
  if (tileOrder_.bytes()) m.push_back({"tile_order", tileOrder_.bytes()});
  return m;
}

void SpFrameCuda::prepareFrame(const FrameSetup& f) {
  buffers_.resize(static_cast<size_t>(f.pixelCount()));
}

void SpFrameCuda::finishFrame(const FrameSetup& f, Image& out, FrameStats& stats) {
  if (hostImageWanted()) downloadImage(f, buffers_, out, stream());
  uint32_t c[3];
  readDevice(c, buffers_.counters.data(), sizeof c, stream());
  stats.unfinishedPixels = buffers_.raysWritePixels ? int64_t{f.pixelCount()} - c[2] : c[1];
  addCacheStats(cache_, stats);
}

namespace {

class SpCuda final : public SpFrameCuda {
 public:
  SpCuda(const SchedulerOptions& o, ProducerKernelsPtr p) : SpFrameCuda(o, std::move(p)) {
    buffers_.raysWritePixels = true;
  }

 private:
  void renderFrame(const FrameSetup& f, Image&, FrameStats& stats) override {
    NvtxRange range("sp frame");
    cache_.beginFrame(f);
    buffers_.order = tileOrder_.next(f, stream());
    runSpLoopCuda(f, cudaProducer(), cache_, buffers_, 0, true, stats, stream());
  }
};

}  // namespace

std::unique_ptr<Scheduler> makeSpCuda(const SchedulerOptions& o, ProducerKernelsPtr producer) {
  return std::make_unique<SpCuda>(o, std::move(producer));
}

}  // namespace gvdp::detail
