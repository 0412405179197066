// The sp loop on the CPU backend (the loop itself: sp_loop.h), shared by `sp` (the whole frame)
// and by `dp` (its sweep of rays a device-side schedule left unfinished).
#pragma once

#include <vector>

#include "gvdp/cache/brick_cache_cpu.h"
#include "gvdp/render/march.h"
#include "gvdp/sched/ray_tasks.h"
#include "gvdp/sched/scheduler.h"

namespace gvdp::detail {

// Runs passes until no ray is left. With `tiled`, the first pass covers every pixel in 8x8
// tiles from a fresh state; otherwise it resumes the `liveCount` rays of `live`. Bricks already
// queued (cache counters) are produced before the first pass. Rays that finish go to `finished`
// (ray_tasks.h; sp's pixels, none for dp's sweep). Adds to stats.passes.
void runSpLoopCpu(const FrameSetup& f, const ProducerKernels& producer, BrickCacheCpu& cache,
                  RayState* payload, FinishedRays finished, std::vector<uint32_t>& live,
                  std::vector<uint32_t>& next, uint32_t liveCount, bool tiled, FrameStats& stats);

// Resolves every pixel to `out`; returns the unfinished ones.
int64_t resolveCpu(const FrameSetup& f, const RayState* payload, Image& out);

// The frame of every cached CPU scheduler (sp, dp, pt): the brick cache and one ray payload per
// pixel, both begun afresh by beginRays() (dp, pt; sp starts its rays from the eye); memory()
// reports them, derived schedulers add theirs.
class SpFrameCpu : public Scheduler {
 public:
  SpFrameCpu(const SchedulerOptions& o, ProducerKernelsPtr producer);
  MemoryReport memory() const override;

 protected:
  void beginRays(const FrameSetup& f);

  BrickCacheCpu cache_;
  std::vector<RayState> payload_;
};

}  // namespace gvdp::detail
