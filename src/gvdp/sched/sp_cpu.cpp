#include <chrono>
#include <vector>

#include "gvdp/base/parallel.h"
#include "gvdp/cache/brick_cache_cpu.h"
#include "gvdp/render/pool_cpu.h"
#include "gvdp/sched/ray_tasks.h"
#include "gvdp/sched/sp.h"

namespace gvdp {
namespace {

class SpCpu final : public Scheduler {
 public:
  explicit SpCpu(const SchedulerOptions& o)
      : cache_(o.poolBricks ? o.poolBricks : DEFAULT_POOL_BRICKS_CPU) {}

  FrameStats render(const FrameSetup& f, Image& out) override {
    auto t0 = std::chrono::steady_clock::now();
    FrameStats stats;
    stats.index = f.frameIndex;
    cache_.beginFrame(f);
    size_t n = static_cast<size_t>(f.pixelCount());
    payload_.assign(n, initialRayState());
    live_.resize(n);
    next_.resize(n);
    CpuPool pool{cache_.texels()};

    uint32_t liveCount = 0;
    for (int pass = 0;; ++pass) {
      CacheView cache = cache_.view();
      uint32_t nextCount = 0;
      auto renderItem = [&](int pixel) {
        if (renderRay(f, cache, pool, payload_.data(), pixel))
          next_[atomicAdd32(&nextCount, 1u)] = static_cast<uint32_t>(pixel);
      };
      if (pass == 0) {
        parallelFor(
            tileCount(f) * TILE * TILE,
            [&](int64_t i) {
              int pixel = tiledPixel(f, static_cast<int>(i));
              if (pixel >= 0) renderItem(pixel);
            },
            TILE * TILE);
      } else {
        parallelFor(
            liveCount, [&](int64_t i) { renderItem(static_cast<int>(live_[i])); }, 32);
      }
      ++stats.passes;
      std::swap(live_, next_);
      liveCount = nextCount;
      if (liveCount == 0) break;

      uint32_t requests =
          std::min<uint32_t>(cache_.counters()[COUNTER_REQUESTS], cache.requestCapacity);
      uint32_t failedBefore = cache_.counters()[COUNTER_FAILED];
      const BrickKey* keys = cache_.requests();
      parallelFor(
          requests, [&](int64_t i) { cache_.produce(f.scene, cache, keys[i]); }, 1);
      cache_.clearRequests();
      if (cache_.counters()[COUNTER_FAILED] != failedBefore && cache_.refill() == 0)
        cache_.setDegraded(true);
      if (stats.passes >= SP_MAX_PASSES) cache_.setDegraded(true);
    }

    out = Image(f.width, f.height);
    uint32_t unfinished = 0;
    parallelFor(
        static_cast<int64_t>(n),
        [&](int64_t i) {
          bool u = false;
          out.pixels[i] = resolveRay(f, payload_.data(), static_cast<int>(i), &u);
          if (u) atomicAdd32(&unfinished, 1u);
        },
        256);
    stats.unfinishedPixels = unfinished;
    stats.degraded = cache_.degraded();
    stats.cache = cache_.frameStats();
    stats.ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return stats;
  }

  MemoryReport memory() const override {
    MemoryReport m = cache_.memory();
    m.push_back({"ray_payload", payload_.size() * sizeof(RayState)});
    m.push_back({"live_ray_lists", (live_.size() + next_.size()) * sizeof(uint32_t)});
    return m;
  }

 private:
  BrickCacheCpu cache_;
  std::vector<RayState> payload_;
  std::vector<uint32_t> live_, next_;
};

}  // namespace

std::unique_ptr<Scheduler> makeSpCpu(const SchedulerOptions& o) {
  return std::make_unique<SpCpu>(o);
}

}  // namespace gvdp
