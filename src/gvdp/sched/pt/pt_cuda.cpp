#include <vector>

#include "gvdp/sched/pt/pt.h"
#include "gvdp/sched/pt/pt_cuda.h"
#include "gvdp/sched/sp/sp_loop_cuda.h"

namespace gvdp {
namespace {

class PtCuda final : public Scheduler {
 public:
  explicit PtCuda(const SchedulerOptions& o)
      : cache_(o.poolBricks ? o.poolBricks : DEFAULT_POOL_BRICKS_CUDA),
        counters_(PT_COUNTER_COUNT * PT_COUNTER_STRIDE),
        blocks_(ptWorkerBlocks()) {}

  FrameStats render(const FrameSetup& f, Image& out) override {
    FrameStats stats;
    stats.index = f.frameIndex;
    resize(f);
    timelineBegin();
    NvtxRange range("pt frame");
    timer_.start();
    cache_.beginFrame(f);
    PtContext ctx = prepare(f);
    {
      NvtxRange kernel("pt persistent kernel");
      launchPtFrame(ctx, cache_.pool(), blocks_);
      GVDP_CUDA_CHECK(cudaGetLastError());
    }
    stats.unfinishedPixels = resolveCuda(f, buffers_);
    timer_.stop();
    stats.ms = timer_.ms();
    timelineEnd(stats);
    downloadImage(f, buffers_, out);
    std::vector<uint32_t> c(counters_.size());
    GVDP_CUDA_CHECK(
        cudaMemcpy(c.data(), counters_.data(), counters_.bytes(), cudaMemcpyDeviceToHost));
    stats.launches = c[PT_PRODUCTIONS * PT_COUNTER_STRIDE] + c[PT_RENDER_TASKS * PT_COUNTER_STRIDE];
    stats.relaunchedRays = c[PT_RELAUNCHED * PT_COUNTER_STRIDE];
    stats.cache = cache_.frameStats();
    stats.degraded = cache_.degraded() || stats.cache.failed != 0;
    return stats;
  }

  MemoryReport memory() const override {
    MemoryReport m = cache_.memory();
    m.push_back({"ray_payload_lists_image", buffers_.bytes()});
    m.push_back({"pt_queues_and_wait_lists",
                 raySlots_.bytes() + taskSlots_.bytes() + freeSlots_.bytes() + taskKey_.bytes() +
                     waitHead_.bytes() + waitNext_.bytes() + counters_.bytes()});
    return m;
  }

 private:
  void resize(const FrameSetup& f) {
    uint32_t n = static_cast<uint32_t>(f.pixelCount());
    buffers_.resize(n);
    if (waitNext_.size() == n) return;
    ids_ = n + static_cast<uint32_t>(blocks_) * 8;  // pixels + worker warps (pt_body.h)
    raySlots_ = DeviceBuffer<uint64_t>(ringCapacity(n));
    taskSlots_ = DeviceBuffer<uint64_t>(ringCapacity(ids_));
    freeSlots_ = DeviceBuffer<uint64_t>(ringCapacity(ids_));
    taskKey_ = DeviceBuffer<BrickKey>(ids_);
    waitHead_ = DeviceBuffer<uint32_t>(ids_);
    waitNext_ = DeviceBuffer<uint32_t>(n);
  }

  // The frame's queues: empty rings, every task id free, every ray fresh and live.
  PtContext prepare(const FrameSetup& f) {
    uint32_t n = static_cast<uint32_t>(f.pixelCount());
    GVDP_CUDA_CHECK(cudaMemset(buffers_.payload.data(), 0, buffers_.payload.bytes()));
    std::vector<uint32_t> c(counters_.size());
    initialPtCounters(c.data(), n, ids_);
    GVDP_CUDA_CHECK(
        cudaMemcpy(counters_.data(), c.data(), counters_.bytes(), cudaMemcpyHostToDevice));
    PtContext ctx = makePtContext(
        f, cache_.view(), buffers_.payload.data(),
        {raySlots_.data(), taskSlots_.data(), freeSlots_.data(),
         static_cast<uint32_t>(raySlots_.size()), static_cast<uint32_t>(taskSlots_.size()),
         taskKey_.data(), waitHead_.data(), waitNext_.data(), counters_.data()});
    launchPtRingsInit(ctx, ids_);
    return ctx;
  }

  BrickCacheCuda cache_;
  SpBuffersCuda buffers_;
  DeviceBuffer<uint32_t> counters_, waitHead_, waitNext_;
  DeviceBuffer<uint64_t> raySlots_, taskSlots_, freeSlots_;
  DeviceBuffer<BrickKey> taskKey_;
  int blocks_;
  uint32_t ids_ = 0;
  GpuTimer timer_;
};

}  // namespace

std::unique_ptr<Scheduler> makePtCuda(const SchedulerOptions& o) {
  return std::make_unique<PtCuda>(o);
}

}  // namespace gvdp
