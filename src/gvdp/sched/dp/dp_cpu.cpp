#include <atomic>
#include <vector>

#include "gvdp/base/clock.h"
#include "gvdp/base/parallel.h"
#include "gvdp/profile/timeline.h"
#include "gvdp/render/brick_pool.h"
#include "gvdp/sched/dp/dp.h"
#include "gvdp/sched/dp/dp_body.h"
#include "gvdp/sched/dp/task_queue.h"
#include "gvdp/sched/sp/sp_loop_cpu.h"

namespace gvdp::detail {
namespace {

struct DpTask {
  bool produce;
  PixelRect rect;  // render task
  BrickKey key;    // production task
  uint32_t* entry;
};

struct CpuLauncher {
  TaskQueue<DpTask>* queue;
  const DpContext* ctx;

  void produce(const BrickKey& key, uint32_t* entry) {
    if (queue->push({true, {}, key, entry})) {
      atomicAdd32(&ctx->counters[DP_PRODUCTIONS], 1u);
    } else {  // a refused launch: the brick is MISSING again, its rays wait for the sweep
      storeRelease32(entry, ENTRY_MISSING);
      atomicAdd32(&ctx->counters[DP_LAUNCH_FAILURES], 1u);
    }
  }
  void relaunch(const PixelRect& r) {
    if (queue->push({false, r, {}, nullptr}))
      atomicAdd32(&ctx->counters[DP_RELAUNCHES], 1u);
    else
      atomicAdd32(&ctx->counters[DP_LAUNCH_FAILURES], 1u);
  }
};

class DpCpu final : public SpFrameCpu {
 public:
  DpCpu(const SchedulerOptions& o, ProducerKernelsPtr producer)
      : SpFrameCpu(o, std::move(producer)), pendingLaunches_(pendingLaunchesOf(o)) {}

  MemoryReport memory() const override {
    MemoryReport m = SpFrameCpu::memory();
    m.push_back({"ray_locks", locks_.size() * sizeof(uint32_t)});
    m.push_back({"task_queue", dpCpuTaskQueueBytes(pendingLaunches_)});
    return m;
  }

 private:
  void renderFrame(const FrameSetup& f, Image& out, FrameStats& stats) override {
    beginRays(f);
    size_t n = static_cast<size_t>(f.pixelCount());
    locks_.assign(n, RAY_FREE);
    uint32_t counters[DP_COUNTER_COUNT] = {};
    CacheView view = cache_.view();
    view.degradeOnFailure = 1;
    BrickPool pool = cache_.pool();
    DpContext ctx{f, view, payload_.data(), locks_.data(), counters, pool, 0};

    // Root launch: the screen in 32x16 tiles (not limited by the pending-launch capacity).
    TaskQueue<DpTask> queue(pendingLaunches_ + static_cast<size_t>(dpTileCount(f)));
    for (int t = 0; t < dpTileCount(f); ++t) {
      int x = (t % ((f.width + DP_TILE_W - 1) / DP_TILE_W)) * DP_TILE_W;
      int y = (t / ((f.width + DP_TILE_W - 1) / DP_TILE_W)) * DP_TILE_H;
      queue.push({false,
                  {x, y, std::min(x + DP_TILE_W, f.width), std::min(y + DP_TILE_H, f.height)},
                  {},
                  nullptr});
    }
    CpuLauncher launcher{&queue, &ctx};
    ThreadPool& threads = ThreadPool::global();
    threads.run(
        threads.size(), 1,
        [&](int64_t, int64_t, int worker) {
          DpTask task;
          while (queue.pop(task)) {
            uint64_t start = clockNanoseconds();
            if (task.produce) {
              producer().produceBrick(ctx.cache, pool, task.key);
              launcher.relaunch(brickScreenRect(f, ctx.cache.clipmap, task.key));
            } else {
              for (int y = task.rect.y0; y < task.rect.y1; ++y)
                for (int x = task.rect.x0; x < task.rect.x1; ++x)
                  dpRenderPixel(ctx, pool, launcher, y * f.width + x);
            }
            if (TaskObserver o = taskObserver())  // one timeline record per task
              o(static_cast<uint8_t>(task.produce ? TaskKind::Produce : TaskKind::Render), worker,
                start, clockNanoseconds());
            queue.finished();
          }
        },
        NO_RECORD);
    sweep(f, stats);
    stats.unfinishedPixels = resolveCpu(f, payload_.data(), out);
    addCacheStats(cache_, stats);
    // Refused launches are finished by the sweep: exact, not degraded.
    stats.degraded = stats.degraded || stats.cache.failed != 0;
    stats.launches = counters[DP_PRODUCTIONS] + counters[DP_RELAUNCHES];
    stats.launchFailures = counters[DP_LAUNCH_FAILURES];
  }

  // Safety net: rays the task schedule left unfinished go through the sp loop.
  void sweep(const FrameSetup& f, FrameStats& stats) {
    live_.clear();
    for (uint32_t i = 0; i < static_cast<uint32_t>(f.pixelCount()); ++i)
      if (!payload_[i].finished(f.lod)) live_.push_back(i);
    stats.sweptPixels = static_cast<int64_t>(live_.size());
    uint32_t c[COUNTER_COUNT];
    cache_.readCounters(c);
    if (live_.empty() && c[COUNTER_REQUESTS] == 0) return;
    next_.resize(f.pixelCount());
    live_.resize(f.pixelCount());
    // A degraded frame keeps degrading; the sweep itself may refill the free list.
    runSpLoopCpu(f, producer(), cache_, payload_.data(), FinishedRays{}, live_, next_,
                 static_cast<uint32_t>(stats.sweptPixels), false, stats);
  }

  size_t pendingLaunches_;
  std::vector<uint32_t> locks_, live_, next_;
};

}  // namespace

size_t dpCpuTaskQueueBytes(size_t pendingLaunches) {
  return pendingLaunches * sizeof(DpTask);
}

std::unique_ptr<Scheduler> makeDpCpu(const SchedulerOptions& o, ProducerKernelsPtr producer) {
  return std::make_unique<DpCpu>(o, std::move(producer));
}

}  // namespace gvdp::detail
