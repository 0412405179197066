// What a frame's timeline says: statistics (busy time per task kind, idle fraction, tail), a
// picture like the paper's Figure 5 (x: SM or worker, y: time from the top; red render, blue
// production, purple both, black idle) and Chrome trace-event JSON (one track per SM; opens in
// Perfetto and chrome://tracing).
#pragma once

#include <string>
#include <vector>

#include "gvdp/io/png.h"
#include "gvdp/profile/timeline.h"

namespace gvdp::detail {

struct TimelineStats {
  double spanMs = 0;                       // first start to last end
  double busyFraction[TASK_KIND_COUNT]{};  // of lanes x span, per kind (union per lane)
  double idleFraction = 0;                 // lanes x span not covered by any task
  double tailMs = 0;  // at the end of the render/production work, the time fewer than half the
                      // lanes are busy (the full-width resolve and cache upkeep excluded)
  int lanes = 0;
  size_t records = 0;
};

TimelineStats timelineStats(const std::vector<TimelineRecord>& records, int lanes);
std::string timelineSummary(const TimelineStats& s);  // one line
Image timelineImage(const std::vector<TimelineRecord>& records, int lanes,
                    const std::string& title);
std::string chromeTraceJson(const std::vector<TimelineRecord>& records, int lanes);

}  // namespace gvdp::detail
