#include <vector>

#include "gvdp/base/parallel.h"
#include "gvdp/profile/timeline.h"
#include "gvdp/render/brick_pool.h"
#include "gvdp/sched/pt/pt.h"
#include "gvdp/sched/pt/pt_body.h"
#include "gvdp/sched/sp/sp_loop_cpu.h"

namespace gvdp {
namespace {

class PtCpu final : public SpFrameCpu {
 public:
  PtCpu(const SchedulerOptions& o, ProducerKernelsPtr p) : SpFrameCpu(o, std::move(p)) {}

  MemoryReport memory() const override {
    MemoryReport m = SpFrameCpu::memory();
    m.push_back({"pt_queues_and_wait_lists",
                 (raySlots_.size() + taskSlots_.size() + freeSlots_.size()) * sizeof(uint64_t) +
                     (waitHead_.size() + waitNext_.size() + counters_.size()) * sizeof(uint32_t) +
                     taskKey_.size() * sizeof(BrickKey)});
    return m;
  }

 private:
  void renderFrame(const FrameSetup& f, Image& out, FrameStats& stats) override {
    beginRays(f);
    PtContext ctx = prepare(f);
    BrickPool pool = cache_.pool();
    ThreadPool& threads = ThreadPool::global();
    threads.run(
        threads.size(), 1, [&](int64_t, int64_t, int worker) { work(ctx, pool, worker); },
        NO_RECORD);
    stats.unfinishedPixels = resolveCpu(f, payload_.data(), out);
    addCacheStats(cache_, stats);
    stats.degraded = stats.degraded || stats.cache.failed != 0;
    stats.launches = *ctx.counter(PT_PRODUCTIONS) + *ctx.counter(PT_RENDER_TASKS);
    stats.relaunchedRays = *ctx.counter(PT_RELAUNCHED);
  }

  PtContext prepare(const FrameSetup& f) {
    uint32_t n = static_cast<uint32_t>(f.pixelCount());
    uint32_t ids = n + static_cast<uint32_t>(ThreadPool::global().size());
    auto initRing = [](std::vector<uint64_t>& slots, uint32_t capacity, uint32_t filled) {
      slots.resize(capacity);
      for (uint32_t i = 0; i < capacity; ++i) slots[i] = ringInitialSlot(i, filled);
    };
    initRing(raySlots_, ringCapacity(n), 0);
    initRing(taskSlots_, ringCapacity(ids), 0);
    initRing(freeSlots_, ringCapacity(ids), ids);
    taskKey_.resize(ids);
    waitHead_.assign(ids, LIST_CLOSED);
    waitNext_.assign(n, LIST_END);
    counters_.resize(PT_COUNTER_COUNT * PT_COUNTER_STRIDE);
    initialPtCounters(counters_.data(), n, ids);
    return makePtContext(
        f, cache_.view(), payload_.data(),
        {raySlots_.data(), taskSlots_.data(), freeSlots_.data(),
         static_cast<uint32_t>(raySlots_.size()), static_cast<uint32_t>(taskSlots_.size()),
         taskKey_.data(), waitHead_.data(), waitNext_.data(), counters_.data()});
  }

  // One worker: production first, then relaunched rays, then fresh tiles, until no ray is left.
  void work(const PtContext& ctx, const BrickPool& pool, int worker) {
    const FrameSetup& f = ctx.frame;
    while (loadAcquire32(ctx.counter(PT_LIVE_RAYS)) != 0) {
      uint64_t start = steadyNanoseconds();
      TaskKind kind = TaskKind::Render;
      uint32_t position = 0, finished = 0;
      if (ringClaim(ctx.tasks, 1, &position)) {
        uint32_t id = ringTake(ctx.tasks, position);
        producer().produceBrick(ctx.cache, pool, loadTaskKey(ctx, id));
        finishProductionTask(ctx, id);
        atomicAdd32(ctx.counter(PT_PRODUCTIONS), 1u);
        kind = TaskKind::Produce;
      } else if (uint32_t n = ringClaim(ctx.rays, PT_BATCH, &position)) {
        uint32_t batch[PT_BATCH];
        for (uint32_t i = 0; i < n; ++i) batch[i] = ringTake(ctx.rays, position + i);
        for (uint32_t i = 0; i < n; ++i) finished += ptRunRay(ctx, pool, batch[i]) ? 1u : 0u;
        atomicAdd32(ctx.counter(PT_RENDER_TASKS), 1u);
      } else if (loadRelaxed32(ctx.counter(PT_NEXT_ITEM)) < ctx.itemCount) {
        uint32_t first = atomicAdd32(ctx.counter(PT_NEXT_ITEM), PT_BATCH);
        for (uint32_t i = first; i < first + PT_BATCH && i < ctx.itemCount; ++i) {
          int pixel = tiledPixel(f, static_cast<int>(i));
          if (pixel >= 0) finished += ptRunRay(ctx, pool, static_cast<uint32_t>(pixel)) ? 1u : 0u;
        }
        atomicAdd32(ctx.counter(PT_RENDER_TASKS), 1u);
      } else {
        spinPause();
        continue;
      }
      if (finished) atomicAdd32(ctx.counter(PT_LIVE_RAYS), 0u - finished);
      if (TaskObserver o = taskObserver())
        o(static_cast<uint8_t>(kind), worker, start, steadyNanoseconds());
    }
  }

  std::vector<uint64_t> raySlots_, taskSlots_, freeSlots_;
  std::vector<uint32_t> waitHead_, waitNext_, counters_;
  std::vector<BrickKey> taskKey_;
};

}  // namespace

std::unique_ptr<Scheduler> makePtCpu(const SchedulerOptions& o, ProducerKernelsPtr producer) {
  return std::make_unique<PtCpu>(o, std::move(producer));
}

}  // namespace gvdp
