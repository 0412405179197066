#include "gvdp/sched/dp/dp.h"
#include "gvdp/sched/producer_kernels_cuda.h"
#include "gvdp/sched/sp/sp_cuda.h"
#include "gvdp/sched/sp/sp_loop_cuda.h"

namespace gvdp::detail {
namespace {

class DpCuda final : public SpFrameCuda {
 public:
  DpCuda(const SchedulerOptions& o, ProducerKernelsPtr producer)
      : SpFrameCuda(o, std::move(producer)),
        pendingLaunches_(pendingLaunchesOf(o)),
        locks_(0),
        counters_(DP_COUNTER_COUNT),
        context_(1) {
    GVDP_INPUT_CHECK(
        cudaProducer().hasDp(),
        "scheduler 'dp' on cuda needs CUDA Dynamic Parallelism: build with GVDP_CDP=ON "
        "and the producer's translation unit with relocatable device code");
    size_t free0 = 0, free1 = 0, total = 0;
    GVDP_CUDA_CHECK(cudaMemGetInfo(&free0, &total));
    {
      WatchedWait wait("the device runtime's new launch buffer");  // waits for the device
      GVDP_CUDA_CHECK(cudaDeviceSetLimit(cudaLimitDevRuntimePendingLaunchCount, pendingLaunches_));
    }
    GVDP_CUDA_CHECK(cudaMemGetInfo(&free1, &total));
    cdpBytes_ = free0 > free1 ? free0 - free1 : 0;
  }

  MemoryReport memory() const override {
    MemoryReport m = SpFrameCuda::memory();
    m.push_back({"ray_locks", locks_.bytes()});
    m.push_back({"cdp_pending_launch_buffer", cdpBytes_});
    return m;
  }

 private:
  void prepareFrame(const FrameSetup& f) override {
    SpFrameCuda::prepareFrame(f);
    size_t n = static_cast<size_t>(f.pixelCount());
    if (locks_.size() != n) locks_ = DeviceBuffer<uint32_t>(n);
    size_t total = 0;
    if (firstFrame_) GVDP_CUDA_CHECK(cudaMemGetInfo(&freeBefore_, &total));
  }

  void renderFrame(const FrameSetup& f, Image&, FrameStats& stats) override {
    NvtxRange range("dp frame");
    cache_.beginFrame(f);
    fillDevice(locks_.data(), 0, locks_.bytes(), stream());  // RAY_FREE
    fillDevice(counters_.data(), 0, counters_.bytes(), stream());
    fillDevice(buffers_.payload.data(), 0, buffers_.payload.bytes(), stream());  // fresh rays
    CacheView view = cache_.view();
    view.degradeOnFailure = 1;
    DpContext ctx{f,
                  view,
                  buffers_.payload.data(),
                  locks_.data(),
                  counters_.data(),
                  cache_.pool(),
                  pendingLaunches_ / 2};
    writeDevice(context_.data(), &ctx, sizeof ctx, stream());
    {
      NvtxRange schedule("dp device schedule");
      cudaProducer().launchDpFrame(context_.data(), f, stream());
      GVDP_CUDA_CHECK(cudaGetLastError());
    }
    sweep(f, stats);  // after the whole tree of device launches: the stream orders it
    resolveCuda(f, buffers_, stream());
  }

  void finishFrame(const FrameSetup& f, Image& out, FrameStats& stats) override {
    if (firstFrame_) {  // what the device runtime took for the first frame's launches
      size_t freeAfter = 0, total = 0;
      GVDP_CUDA_CHECK(cudaMemGetInfo(&freeAfter, &total));
      cdpBytes_ += freeBefore_ > freeAfter ? freeBefore_ - freeAfter : 0;
      firstFrame_ = false;
    }
    SpFrameCuda::finishFrame(f, out, stats);
    uint32_t c[DP_COUNTER_COUNT];
    readDevice(c, counters_.data(), sizeof c, stream());
    stats.launches = c[DP_PRODUCTIONS] + c[DP_RELAUNCHES];
    stats.launchFailures = c[DP_LAUNCH_FAILURES];
    stats.deferred = c[DP_DEFERRED];
    // Refused launches are finished by the sweep: exact, not degraded.
    stats.degraded = stats.degraded || stats.cache.failed != 0;
  }

  // Rays the device-side schedule left unfinished (refused launches, deferred productions) are
  // finished by the sp loop; with the race-free relaunch there are none otherwise. In a budgeted
  // frame, the claims past its deadline are queued (LaunchProduction): the loop produces them.
  void sweep(const FrameSetup& f, FrameStats& stats) {
    NvtxRange range("dp sweep");
    fillDevice(buffers_.counters.data(), 0, 4, stream());
    launchCompactUnfinished(f, buffers_.payload.data(), buffers_.live.data(),
                            buffers_.counters.data(), stream());
    uint32_t unfinished = 0;
    readDevice(&unfinished, buffers_.counters.data(), 4, stream());
    stats.sweptPixels = unfinished;
    if (unfinished || cache_.budgeted())
      runSpLoopCuda(f, cudaProducer(), cache_, buffers_, unfinished, false, stats, stream());
  }

  uint32_t pendingLaunches_;
  DeviceBuffer<uint32_t> locks_, counters_;
  DeviceBuffer<DpContext> context_;  // the frame's, read by every device-side task
  size_t cdpBytes_ = 0, freeBefore_ = 0;
  bool firstFrame_ = true;
};

}  // namespace

std::unique_ptr<Scheduler> makeDpCuda(const SchedulerOptions& o, ProducerKernelsPtr producer) {
  return std::make_unique<DpCuda>(o, std::move(producer));
}

}  // namespace gvdp::detail
