#include "gvdp/sched/sp_cuda.h"
#include "gvdp/base/cuda_util.h"
#include "gvdp/cache/brick_cache_cuda.h"
#include "gvdp/sched/sp.h"

namespace gvdp {
namespace {

class SpCuda final : public Scheduler {
 public:
  explicit SpCuda(const SchedulerOptions& o)
      : cache_(o.poolBricks ? o.poolBricks : DEFAULT_POOL_BRICKS_CUDA), passCounters_(2) {}

  FrameStats render(const FrameSetup& f, Image& out) override {
    FrameStats stats;
    stats.index = f.frameIndex;
    size_t n = static_cast<size_t>(f.pixelCount());
    if (payload_.size() != n) {
      payload_ = DeviceBuffer<RayState>(n);
      live_ = DeviceBuffer<uint32_t>(n);
      next_ = DeviceBuffer<uint32_t>(n);
      image_ = DeviceBuffer<uint32_t>(n);
    }
    timer_.start();
    cache_.beginFrame(f);
    GVDP_CUDA_CHECK(cudaMemset(passCounters_.data(), 0, passCounters_.bytes()));
    launchFirstRenderPass(f, cache_.view(), cache_.pool(), payload_.data(), next_.data(),
                          passCounters_.data());
    for (;;) {
      GVDP_CUDA_CHECK(cudaGetLastError());
      ++stats.passes;
      // The GigaVoxels loop: the host reads the counts after every pass.
      uint32_t stopped = 0, counters[COUNTER_COUNT];
      GVDP_CUDA_CHECK(cudaMemcpy(&stopped, passCounters_.data(), 4, cudaMemcpyDeviceToHost));
      if (stopped == 0) break;
      cache_.readCounters(counters);
      uint32_t requests = std::min(counters[COUNTER_REQUESTS], cache_.view().requestCapacity);
      launchProduce(f, cache_.view(), cache_.pool(), requests);
      cache_.clearRequests();
      uint32_t after[COUNTER_COUNT];
      cache_.readCounters(after);
      if (after[COUNTER_FAILED] != counters[COUNTER_FAILED] && cache_.refill() == 0)
        cache_.setDegraded(true);
      if (stats.passes >= SP_MAX_PASSES) cache_.setDegraded(true);
      std::swap(live_, next_);
      GVDP_CUDA_CHECK(cudaMemset(passCounters_.data(), 0, 4));
      launchRenderPass(f, cache_.view(), cache_.pool(), payload_.data(), live_.data(), stopped,
                       next_.data(), passCounters_.data());
    }
    launchResolve(f, payload_.data(), image_.data(), passCounters_.data());
    GVDP_CUDA_CHECK(cudaGetLastError());
    timer_.stop();
    stats.ms = timer_.ms();
    uint32_t counts[2];
    GVDP_CUDA_CHECK(cudaMemcpy(counts, passCounters_.data(), 8, cudaMemcpyDeviceToHost));
    stats.unfinishedPixels = counts[1];
    stats.degraded = cache_.degraded();
    stats.cache = cache_.frameStats();
    out = Image(f.width, f.height);
    GVDP_CUDA_CHECK(cudaMemcpy(out.pixels.data(), image_.data(), n * 4, cudaMemcpyDeviceToHost));
    return stats;
  }

  MemoryReport memory() const override {
    MemoryReport m = cache_.memory();
    m.push_back({"ray_payload", payload_.bytes()});
    m.push_back({"live_ray_lists", live_.bytes() + next_.bytes()});
    m.push_back({"image", image_.bytes()});
    return m;
  }

 private:
  BrickCacheCuda cache_;
  DeviceBuffer<RayState> payload_;
  DeviceBuffer<uint32_t> live_, next_, image_, passCounters_;
  GpuTimer timer_;
};

}  // namespace

std::unique_ptr<Scheduler> makeSpCuda(const SchedulerOptions& o) {
  return std::make_unique<SpCuda>(o);
}

}  // namespace gvdp
