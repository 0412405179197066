#include <algorithm>
#include <optional>
#include <vector>

#include "gvdp/base/clock.h"
#include "gvdp/base/parallel.h"
#include "gvdp/profile/timeline.h"
#include "gvdp/render/brick_pool.h"
#include "gvdp/sched/pt/pt.h"
#include "gvdp/sched/pt/pt_body.h"
#include "gvdp/sched/pt/pt_stats.h"
#include "gvdp/sched/sp/sp_loop_cpu.h"

namespace gvdp::detail {
namespace {

class PtCpu final : public SpFrameCpu {
 public:
  PtCpu(const SchedulerOptions& o, ProducerKernelsPtr p)
      : SpFrameCpu(o, std::move(p)),
        lookahead_(o.lookahead),
        tailLookahead_(ptTailLookahead(o)),
        prefetch_(o.prefetch, o.farPrefetch) {}

  MemoryReport memory() const override {
    MemoryReport m = SpFrameCpu::memory();
    m.push_back({"pt_queues_and_wait_lists", layout_.bytes()});
    return m;
  }

 private:
  void renderFrame(const FrameSetup& f, Image& out, FrameStats& stats) override {
    beginRays(f);
    PtContext ctx = prepare(f);
    BrickPool pool = cache_.pool();
    ThreadPool& threads = ThreadPool::global();
    threads.run(
        threads.size(), 1,
        [&](int64_t, int64_t, int worker) {
          Worker w{ctx, pool, producer(), worker};
          ptWorkerLoop(ctx, w);
        },
        NO_RECORD);
    stats.unfinishedPixels = resolveCpu(f, payload_.data(), out);
    addCacheStats(cache_, stats);
    stats.degraded = stats.degraded || stats.cache.failed != 0;
    prefetch_.ended(counters_.data(), stats);
    previous_ = f;
  }

  PtContext prepare(const FrameSetup& f) {
    const PtLayout last = layout_;
    layout_ = {static_cast<uint32_t>(f.pixelCount()),
               static_cast<uint32_t>(ThreadPool::global().size())};
    // The rings as the last frame left them if it left them quiet (ptRingsQuiet), as on the GPU.
    const bool keepRings = last.pixels == layout_.pixels && last.workers == layout_.workers &&
                           counters_.size() == PtLayout::COUNTERS &&
                           ptRingsQuiet(counters_.data(), layout_);
    auto initRing = [](std::vector<uint64_t>& slots, uint32_t capacity, uint32_t filled) {
      slots.resize(capacity);
      for (uint32_t i = 0; i < capacity; ++i) slots[i] = ringInitialSlot(i, filled);
    };
    if (!keepRings) {
      initRing(raySlots_, layout_.rayCapacity(), ptRingFilled(0, layout_));
      initRing(taskSlots_, layout_.taskCapacity(), ptRingFilled(1, layout_));
      initRing(freeSlots_, layout_.freeCapacity(), ptRingFilled(PT_FREE_RING, layout_));
      initRing(lookaheadSlots_, PtLayout::lookaheadCapacity(), ptRingFilled(3, layout_));
      initRing(prefetchSlots_, PtLayout::prefetchCapacity(), ptRingFilled(4, layout_));
    }
    taskKey_.resize(layout_.taskIds());
    waitHead_.assign(layout_.taskIds(), LIST_CLOSED);
    waitNext_.assign(layout_.pixels, LIST_END);
    counters_.resize(PtLayout::COUNTERS);
    PtContext ctx = makePtContext(f, cache_.view(), payload_.data(),
                                  {raySlots_.data(), taskSlots_.data(), freeSlots_.data(),
                                   lookaheadSlots_.data(), prefetchSlots_.data(), taskKey_.data(),
                                   waitHead_.data(), waitNext_.data(), counters_.data(), layout_},
                                  lookahead_, tailLookahead_);
    setPrefetch(ctx, f, previous_ ? &*previous_ : nullptr, prefetch_.next(cache_.budgeted()));
    prefetch_.started(ctx);
    initialPtCounters(counters_.data(), layout_, keepRings, ctx.prefetchPoses > 1);
    return ctx;
  }

  // One worker (a thread) of pt's loop; each task is a record of the timeline.
  struct Worker {
    const PtContext& ctx;
    const BrickPool& pool;
    const ProducerKernels& producer;
    int worker;

    uint32_t liveWork() const { return loadAcquire32(ctx.counter(PT_LIVE_WORK)); }
    uint32_t claim(const Ring& r, uint32_t n, uint32_t* position) const {
      return ringClaim(r, n, position);
    }
    void produce(uint32_t position) const {
      timed(TaskKind::Produce, [&] {
        uint32_t id = ringTake(ctx.tasks, position);
        BrickKey key = loadTaskKey(ctx, id);
        producer.produceBrick(ctx.cache, pool, key);
        markIfPrefetched(ctx, id, key);
        finishProductionTask(ctx, id);
        atomicAdd32(ctx.counter(PT_PRODUCTIONS), 1u);
      });
    }
    // The pixels of a batch of rays.
    struct Batch {
      uint32_t n = 0;
      bool relaunched = false;
      int pixels[PT_BATCH];
    };
    Batch queued(uint32_t position, uint32_t n) const {
      Batch b{n, true, {}};
      for (uint32_t i = 0; i < n; ++i)
        b.pixels[i] = static_cast<int>(ringTake(ctx.rays, position + i));
      return b;
    }
    uint32_t claimFresh() const { return claimFreshItems(ctx); }
    Batch fresh(uint32_t first) const {
      Batch b{ctx.itemCount - first < PT_BATCH ? ctx.itemCount - first : PT_BATCH, false, {}};
      for (uint32_t i = 0; i < b.n; ++i)
        b.pixels[i] = orderedPixel(ctx.frame, ctx.tiles, static_cast<int>(first + i));
      return b;
    }
    void render(const Batch& b) const {
      timed(TaskKind::Render, [&] { renderRays(b); });
    }
    // A production is one thread's: produce does all of it.
    static uint32_t producing() { return NO_PRODUCTION; }
    static uint32_t findProduction() { return NO_PRODUCTION; }
    static bool helpsFirst() { return false; }
    static bool renders() { return true; }
    static bool takesTasks() { return true; }
    static void help(uint32_t) {}
    uint32_t claimPrefetch() const { return claimPrefetchItems(ctx); }
    void prefetch(uint32_t first) const {
      timed(TaskKind::Prefetch, [&] {
        uint32_t entered = 0;
        for (uint32_t i = first; i < first + PT_BATCH && i < ctx.prefetchItems; ++i)
          entered += prefetchRay(ctx, pool, i);
        if (entered != 0) atomicAdd32(ctx.counter(PT_PREFETCH_ENTERED), entered);
      });
    }
    void idle() const { spinPause(); }
    void finish() const {}

    // Runs a batch's rays (a pixel < 0 is none) until each finishes or parks.
    void renderRays(const Batch& b) const {
      uint32_t finished = 0;
      for (uint32_t i = 0; i < b.n; ++i) {
        int p = b.pixels[i];
        if (p >= 0 && ptRunRay(ctx, pool, p, b.relaunched)) ++finished;
      }
      if (finished) {
        atomicAdd32(ctx.counter(PT_LIVE_RAYS), 0u - finished);
        atomicAdd32(ctx.counter(PT_LIVE_WORK), 0u - finished);
      }
      atomicAdd32(ctx.counter(PT_RENDER_TASKS), 1u);
    }
    template <class Task>
    void timed(TaskKind kind, Task task) const {
      uint64_t start = clockNanoseconds();
      task();
      if (TaskObserver o = taskObserver())
        o(static_cast<uint8_t>(kind), worker, start, clockNanoseconds());
    }
  };

  uint32_t lookahead_, tailLookahead_;
  PrefetchHistory prefetch_;
  std::optional<FrameSetup> previous_;  // the last frame rendered (the prefetch's prediction)
  PtLayout layout_{};
  std::vector<uint64_t> raySlots_, taskSlots_, freeSlots_, lookaheadSlots_, prefetchSlots_;
  std::vector<uint32_t> waitHead_, waitNext_, counters_;
  std::vector<BrickKey> taskKey_;
};

}  // namespace

std::unique_ptr<Scheduler> makePtCpu(const SchedulerOptions& o, ProducerKernelsPtr producer) {
  return std::make_unique<PtCpu>(o, std::move(producer));
}

}  // namespace gvdp::detail
