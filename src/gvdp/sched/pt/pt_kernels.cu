// The start of a pt frame in one kernel (the worker kernel: pt_worker.cuh).
#include "gvdp/profile/parallel_for.cuh"
#include "gvdp/sched/pt/pt_cuda.h"

namespace gvdp::detail {
namespace {
struct Filled {  // a ring whose first `filled` positions hold the ids 0, 1, ...
  Ring ring;
  uint32_t filled;
};
}  // namespace

void launchPtFrameStart(const PtContext& ctx, const PtLayout& layout, bool keepRings,
                        uint32_t* resolveCount, cudaStream_t stream) {
  const Ring order[PT_RINGS] = {ctx.rays, ctx.tasks, ctx.freeIds, ctx.lookaheadIds,
                                ctx.prefetchIds};
  Filled rings[PT_RINGS];
  for (uint32_t r = 0; r < PT_RINGS; ++r) rings[r] = {order[r], ptRingFilled(r, layout)};
  uint32_t slots = 0;
  if (!keepRings)
    for (const Filled& r : rings) slots += r.ring.mask + 1;
  const uint32_t first = keepRings ? static_cast<uint32_t>(PT_FIRST_FRAME_COUNTER) : 0u;
  const uint32_t total = slots + static_cast<uint32_t>(PtLayout::COUNTERS) - first + 1;
  uint32_t* counters = ctx.counters;
  const bool far = ctx.prefetchPoses > 1;
  parallelForCuda("pt: frame start", stream, total, ctx.frame.timeline, TaskKind::Cache,
                  [=] __device__(uint32_t i) {
                    if (i == total - 1) {
                      *resolveCount = 0;
                    } else if (i >= slots) {
                      uint32_t c = i - slots + first;
                      counters[c] = initialPtCounter(c, layout, far);
                    } else {
                      int k = 0;
                      while (i > rings[k].ring.mask) i -= rings[k++].ring.mask + 1;
                      rings[k].ring.slots[i] = ringInitialSlot(i, rings[k].filled);
                    }
                  });
}

}  // namespace gvdp::detail
