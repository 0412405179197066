// pt's frame statistics from its counters `c` (PtCounter, PT_COUNTER_STRIDE apart) at a frame's
// end, for both backends: tasks run, rays relaunched (in all, and the longest wait list), whether
// it was a spike (GPU), lookahead and prefetch claims, the prefetch's rays of the `prefetchItems`
// it offered, and any ray left live as unfinished.
// Returns what the prefetch did (the next frame's density follows it: prefetchStrideAfter).
#pragma once

#include <algorithm>

#include "gvdp/sched/pt/pt_prefetch.h"
#include "gvdp/sched/scheduler.h"

namespace gvdp::detail {

inline PrefetchYield addPtStats(const uint32_t* c, uint32_t prefetchItems, uint32_t nearItems,
                                FrameStats& stats) {
  auto counter = [&](PtCounter k) { return c[static_cast<size_t>(k) * PT_COUNTER_STRIDE]; };
  PrefetchYield prefetch = prefetchYield(c, prefetchItems, nearItems);
  stats.launches = uint64_t{counter(PT_PRODUCTIONS)} + counter(PT_RENDER_TASKS);
  stats.relaunchedRays = counter(PT_RELAUNCHED);
  stats.longestWaitList = counter(PT_LONGEST_LIST);
  stats.spike = counter(PT_SPIKE) != 0;
  stats.lookaheadClaims = counter(PT_LOOKAHEAD);
  stats.prefetchClaims = prefetch.claims;
  stats.prefetchRays = prefetch.rays;
  stats.prefetchItems = prefetchItems;
  stats.prefetchEntered = prefetch.entered;
  stats.unfinishedPixels = std::max<int64_t>(stats.unfinishedPixels, counter(PT_LIVE_RAYS));
  return prefetch;
}

// The prefetch from frame to frame, for the host of either backend: its density (`stride`, 0:
// off) and far poses, what the last frame's prefetch did, and the next frame's plan from it.
class PrefetchHistory {
 public:
  PrefetchHistory(uint32_t stride, uint32_t farPoses) : stride_(stride), farPoses_(farPoses) {}

  // A budgeted frame has no far prefetch: it would hold the frame open past its deadline.
  PrefetchPlan next(bool budgeted) const {
    return prefetchPlanAfter(stride_, budgeted ? 0u : farPoses_, last_, lastPoses_);
  }
  void started(const PtContext& ctx) {
    items_ = ctx.prefetchItems;
    nearItems_ = ctx.nearGrid.items();  // (no prefetch: prefetchYield's rays are 0 anyway)
    poses_ = ctx.prefetchPoses;
  }
  // The frame's pt statistics from its counters `c` (addPtStats).
  void ended(const uint32_t* c, FrameStats& stats) {
    last_ = addPtStats(c, items_, nearItems_, stats);
    lastPoses_ = poses_;
  }

 private:
  uint32_t stride_, farPoses_;
  PrefetchYield last_;
  uint32_t lastPoses_ = 1;
  uint32_t items_ = 0, nearItems_ = 0, poses_ = 1;  // the frame's, from its start to its end
};

}  // namespace gvdp::detail
