#include <algorithm>
#include <optional>
#include <vector>

#include "gvdp/base/cuda_util.h"
#include "gvdp/sched/producer_kernels_cuda.h"
#include "gvdp/sched/pt/pt.h"
#include "gvdp/sched/pt/pt_cuda.h"
#include "gvdp/sched/pt/pt_stats.h"
#include "gvdp/sched/sp/sp_cuda.h"
#include "gvdp/sched/sp/sp_loop_cuda.h"

namespace gvdp::detail {
namespace {

// The backlog from which a frame of `share` has no producer SMs: twice the one at which every SM
// of the device would produce (pt_worker.cuh: roleNow). A frame from an empty cache is a spike
// from its start (backlog 0): below the spike, a backlog between the two makes every SM a
// producer and none render, and perlin's frame 0 (240 000 tasks, most of them EMPTY bricks)
// hovered there: 64-67 ms in 2 of 3 runs against 34-38 ms once a spike (H200, BENCHMARKS.md
// session 59). Lowering the backlog for every frame instead cost the 25 cells' FPS 3-8%.
uint32_t spikeBacklogOf(uint32_t share) {
  return 2 * share * static_cast<uint32_t>(smCount());
}

class PtCuda final : public SpFrameCuda {
 public:
  PtCuda(const SchedulerOptions& o, ProducerKernelsPtr producer)
      : SpFrameCuda(o, std::move(producer)),
        counters_(PtLayout::COUNTERS),
        lookaheadSlots_(PtLayout::lookaheadCapacity()),
        prefetchSlots_(PtLayout::prefetchCapacity()),
        blocks_(cudaProducer().ptWorkerBlocks()),
        lookahead_(o.lookahead),
        tailLookahead_(ptTailLookahead(o)),
        prefetch_(o.prefetch, o.farPrefetch),
        workers_(static_cast<uint32_t>(blocks_) * PT_WORKER_WARPS),
        stage_(size_t{workers_} * BRICK_SAMPLE_COUNT),
        productionKey_(workers_),
        productionCounters_(3 * size_t{workers_} + (workers_ + 31) / 32) {
    // zeros: no open bit; and the words a production's atomic exchanges read are initialised
    fillDevice(productionCounters_.data(), 0, productionCounters_.bytes(), stream());
    fillDevice(productionKey_.data(), 0, productionKey_.bytes(), stream());
    fillDevice(stage_.data(), 0, stage_.bytes(), stream());
    cache_.deferTableBoxes();  // grown after the worker's launch (renderFrame)
  }

  MemoryReport memory() const override {
    MemoryReport m = SpFrameCuda::memory();
    m.push_back({"pt_queues_and_wait_lists", layout_.bytes()});
    m.push_back(
        {"pt_productions", stage_.bytes() + productionKey_.bytes() + productionCounters_.bytes()});
    return m;
  }

 private:
  void prepareFrame(const FrameSetup& f) override {
    SpFrameCuda::prepareFrame(f);
    resize(f);
  }
  void renderFrame(const FrameSetup& f, Image&, FrameStats&) override {
    NvtxRange range("pt frame");
    cache_.beginFrame(f);
    PtContext ctx = prepare(f);
    {
      NvtxRange kernel("pt persistent kernel");
      cudaProducer().launchPtFrame(ctx, cache_.pool(), blocks_, stream());
    }
    cache_.growTableBoxes();  // deferred: its blocks take what the worker's leave
    launchResolve(f, buffers_.payload.data(), buffers_.image.data(), buffers_.counters.data(),
                  stream());  // its count zeroed by the frame's start
    previous_ = f;
  }
  void finishFrame(const FrameSetup& f, Image& out, FrameStats& stats) override {
    SpFrameCuda::finishFrame(f, out, stats);
    std::vector<uint32_t> c(counters_.size());
    readDevice(c.data(), counters_.data(), counters_.bytes(), stream());
    prefetch_.ended(c.data(), stats);
    stats.degraded = stats.degraded || stats.cache.failed != 0;
    ringsQuiet_ = ptRingsQuiet(c.data(), layout_);
  }

  void resize(const FrameSetup& f) {
    uint32_t n = static_cast<uint32_t>(f.pixelCount());
    if (waitNext_.size() == n) return;
    ringsQuiet_ = false;  // new rings
    layout_ = {n, workers_};
    raySlots_ = DeviceBuffer<uint64_t>(layout_.rayCapacity());
    taskSlots_ = DeviceBuffer<uint64_t>(layout_.taskCapacity());
    freeSlots_ = DeviceBuffer<uint64_t>(layout_.freeCapacity());
    taskKey_ = DeviceBuffer<BrickKey>(layout_.taskIds());
    waitHead_ = DeviceBuffer<uint32_t>(layout_.taskIds());
    waitNext_ = DeviceBuffer<uint32_t>(n);
  }

  // The frame's queues: empty rings, every task id free, every ray fresh and live; its prefetch.
  PtContext prepare(const FrameSetup& f) {
    PtContext ctx = makePtContext(f, cache_.view(), buffers_.payload.data(),
                                  {raySlots_.data(), taskSlots_.data(), freeSlots_.data(),
                                   lookaheadSlots_.data(), prefetchSlots_.data(), taskKey_.data(),
                                   waitHead_.data(), waitNext_.data(), counters_.data(), layout_},
                                  lookahead_, tailLookahead_);
    setPrefetch(ctx, f, previous_ ? &*previous_ : nullptr, prefetch_.next(cache_.budgeted()));
    prefetch_.started(ctx);
    uint32_t* words = productionCounters_.data();
    ctx.productions = {stage_.data(),        productionKey_.data(), words,
                       words + workers_,     words + 2 * workers_,  words + 3 * workers_,
                       (workers_ + 31) / 32, ctx.counter(PT_OPEN)};
    ctx.producerShare = producerShare_;
    ctx.spikeBacklog = cache_.startedEmpty() ? 0u : spikeBacklog_;  // (spikeBacklogOf)
    ctx.spikeProducers = spikeProducers_;
    ctx.tiles = tileOrder_.next(f, stream());
    launchPtFrameStart(ctx, layout_, ringsQuiet_, buffers_.counters.data() + 1, stream());
    ringsQuiet_ = false;  // until this frame's end says so
    return ctx;
  }

  DeviceBuffer<uint32_t> counters_, waitHead_, waitNext_;
  DeviceBuffer<uint64_t> raySlots_, taskSlots_, freeSlots_, lookaheadSlots_, prefetchSlots_;
  DeviceBuffer<BrickKey> taskKey_;
  int blocks_;
  uint32_t lookahead_, tailLookahead_;
  PrefetchHistory prefetch_;
  std::optional<FrameSetup> previous_;  // the last frame rendered (the prefetch's prediction)
  uint32_t workers_;                    // warps of the persistent kernel
  DeviceBuffer<Rgba8> stage_;
  DeviceBuffer<BrickKey> productionKey_;
  DeviceBuffer<uint32_t> productionCounters_;  // next, done, nonEmpty per worker; open bits
  PtLayout layout_{};
  bool ringsQuiet_ = false;  // the last frame left the rings as a frame starts them
  uint32_t producerShare_ = ptProducerShareFromEnvironment();
  uint32_t spikeBacklog_ = spikeBacklogOf(producerShare_);
  uint32_t spikeProducers_ = static_cast<uint32_t>(smCount()) * PT_SPIKE_PRODUCER_EIGHTHS / 8;
};

}  // namespace

std::unique_ptr<Scheduler> makePtCuda(const SchedulerOptions& o, ProducerKernelsPtr producer) {
  return std::make_unique<PtCuda>(o, std::move(producer));
}

}  // namespace gvdp::detail
