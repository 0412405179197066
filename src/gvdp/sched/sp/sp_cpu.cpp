#include <vector>

#include "gvdp/base/parallel.h"
#include "gvdp/profile/timeline.h"
#include "gvdp/render/brick_pool.h"
#include "gvdp/sched/ray_tasks.h"
#include "gvdp/sched/sp/sp.h"
#include "gvdp/sched/sp/sp_loop.h"
#include "gvdp/sched/sp/sp_loop_cpu.h"

namespace gvdp::detail {

namespace {
// The sp loop's steps on the CPU backend (sp_loop.h).
struct SpStepsCpu {
  const FrameSetup& f;
  const ProducerKernels& producer;
  BrickCacheCpu& cache_;
  RayState* payload;
  FinishedRays finished;
  std::vector<uint32_t>& live;
  std::vector<uint32_t>& next;

  BrickCacheCpu& cache() { return cache_; }

  void produce(uint32_t requests) {
    CacheView view = cache_.view();
    BrickPool pool = cache_.pool();
    const BrickKey* keys = cache_.requests();
    parallelFor(
        requests, [&](int64_t i) { producer.produceBrick(view, pool, keys[i]); }, 1,
        static_cast<uint8_t>(TaskKind::Produce));
  }

  uint32_t renderPass(bool tiled, uint32_t liveCount) {
    CacheView view = cache_.view();
    BrickPool pool = cache_.pool();
    uint32_t nextCount = 0;
    auto renderItem = [&](int pixel) {
      if (renderRay(f, view, pool, payload, pixel, tiled, finished))
        next[atomicAdd32(&nextCount, 1u)] = static_cast<uint32_t>(pixel);
    };
    if (tiled) {
      parallelFor(
          tileCount(f) * TILE * TILE,
          [&](int64_t i) {
            int pixel = tiledPixel(f, static_cast<int>(i));
            if (pixel >= 0) renderItem(pixel);
          },
          TILE * TILE, static_cast<uint8_t>(TaskKind::Render));
    } else {
      parallelFor(
          liveCount, [&](int64_t i) { renderItem(static_cast<int>(live[i])); }, 32,
          static_cast<uint8_t>(TaskKind::Render));
    }
    std::swap(live, next);
    return nextCount;
  }
};
}  // namespace

void runSpLoopCpu(const FrameSetup& f, const ProducerKernels& producer, BrickCacheCpu& cache,
                  RayState* payload, FinishedRays finished, std::vector<uint32_t>& live,
                  std::vector<uint32_t>& next, uint32_t liveCount, bool tiled, FrameStats& stats) {
  SpStepsCpu steps{f, producer, cache, payload, finished, live, next};
  runSpLoop(steps, liveCount, tiled, stats);
}

int64_t resolveCpu(const FrameSetup& f, const RayState* payload, Image& out) {
  out = Image(f.width, f.height);
  uint32_t unfinished = 0;
  parallelFor(
      f.pixelCount(),
      [&](int64_t i) {
        bool u = false;
        out.pixels[i] = resolveRay(f, payload, static_cast<int>(i), &u);
        if (u) atomicAdd32(&unfinished, 1u);
      },
      256, static_cast<uint8_t>(TaskKind::Resolve));
  return unfinished;
}

SpFrameCpu::SpFrameCpu(const SchedulerOptions& o, ProducerKernelsPtr producer)
    : Scheduler(Backend::Cpu, std::move(producer)), cache_(poolBricksOf(o)) {
  cache_.setBudget(budgetNsOf(o));
}

MemoryReport SpFrameCpu::memory() const {
  MemoryReport m = cache_.memory();
  m.push_back({"ray_payload", payload_.size() * sizeof(RayState)});
  return m;
}

void SpFrameCpu::beginRays(const FrameSetup& f) {
  cache_.beginFrame(f);
  payload_.assign(static_cast<size_t>(f.pixelCount()), initialRayState());
}

namespace {

class SpCpu final : public SpFrameCpu {
 public:
  SpCpu(const SchedulerOptions& o, ProducerKernelsPtr p) : SpFrameCpu(o, std::move(p)) {}

  MemoryReport memory() const override {
    MemoryReport m = SpFrameCpu::memory();
    m.push_back({"live_ray_lists", (live_.size() + next_.size()) * sizeof(uint32_t)});
    return m;
  }

 private:
  void renderFrame(const FrameSetup& f, Image& out, FrameStats& stats) override {
    // The first pass starts every ray from the eye (renderRay's `fresh`): the payloads need no
    // initial states, only room for the rays that stop.
    cache_.beginFrame(f);
    size_t n = static_cast<size_t>(f.pixelCount());
    payload_.resize(n);
    live_.resize(n);
    next_.resize(n);
    // Rays write their pixels as they finish (ray_tasks.h: FinishedRays): no resolve pass.
    out = Image(f.width, f.height);
    uint32_t finished = 0;
    runSpLoopCpu(f, producer(), cache_, payload_.data(), {out.pixels.data(), &finished}, live_,
                 next_, 0, true, stats);
    stats.unfinishedPixels = f.pixelCount() - int64_t{finished};
    addCacheStats(cache_, stats);
  }

  std::vector<uint32_t> live_, next_;
};

}  // namespace

std::unique_ptr<Scheduler> makeSpCpu(const SchedulerOptions& o, ProducerKernelsPtr producer) {
  return std::make_unique<SpCpu>(o, std::move(producer));
}

}  // namespace gvdp::detail
