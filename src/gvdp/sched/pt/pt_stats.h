// pt's frame statistics from its counters `c` (PtCounter, PT_COUNTER_STRIDE apart) at a frame's
// end, for both backends: tasks run, rays relaunched (in all, and the longest wait list), whether
// it was a spike (GPU), lookahead and prefetch claims, the prefetch's rays of the `prefetchItems`
// it offered, and any ray left live as unfinished.
// Returns what the prefetch did (the next frame's density follows it: prefetchStrideAfter).
#pragma once

#include <algorithm>

#include "gvdp/sched/pt/pt_body.h"
#include "gvdp/sched/scheduler.h"

namespace gvdp::detail {

inline PrefetchYield addPtStats(const uint32_t* c, uint32_t prefetchItems, FrameStats& stats) {
  auto counter = [&](PtCounter k) { return c[static_cast<size_t>(k) * PT_COUNTER_STRIDE]; };
  PrefetchYield prefetch = prefetchYield(c, prefetchItems);
  stats.launches = uint64_t{counter(PT_PRODUCTIONS)} + counter(PT_RENDER_TASKS);
  stats.relaunchedRays = counter(PT_RELAUNCHED);
  stats.longestWaitList = counter(PT_LONGEST_LIST);
  stats.spike = counter(PT_SPIKE) != 0;
  stats.lookaheadClaims = counter(PT_LOOKAHEAD);
  stats.prefetchClaims = prefetch.claims;
  stats.prefetchRays = prefetch.rays;
  stats.prefetchItems = prefetchItems;
  stats.unfinishedPixels = std::max<int64_t>(stats.unfinishedPixels, counter(PT_LIVE_RAYS));
  return prefetch;
}

}  // namespace gvdp::detail
