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

void launchPtFrameStart(const PtContext& ctx, const PtLayout& layout, cudaStream_t stream) {
  const Filled rings[] = {{ctx.rays, 0},
                          {ctx.tasks, 0},
                          {ctx.freeIds, layout.freeIds()},
                          {ctx.lookaheadIds, PT_LOOKAHEAD_IDS},
                          {ctx.prefetchIds, PT_PREFETCH_IDS}};
  uint32_t slots = 0;
  for (const Filled& r : rings) slots += r.ring.mask + 1;
  const uint32_t payloads = slots + layout.pixels;
  const uint32_t total = payloads + static_cast<uint32_t>(PtLayout::COUNTERS);
  RayState* payload = ctx.payload;
  uint32_t* counters = ctx.counters;
  parallelForCuda("pt: frame start", stream, total, TimelineView{}, TaskKind::Cache,
                  [=] __device__(uint32_t i) {
                    if (i >= payloads) {
                      counters[i - payloads] = initialPtCounter(i - payloads, layout);
                    } else if (i >= slots) {
                      payload[i - slots] = initialRayState();
                    } else {
                      int k = 0;
                      while (i > rings[k].ring.mask) i -= rings[k++].ring.mask + 1;
                      rings[k].ring.slots[i] = ringInitialSlot(i, rings[k].filled);
                    }
                  });
}

}  // namespace gvdp::detail
