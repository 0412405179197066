// The CPU timeline: while a frame is recorded, every task run on the thread pool (a
// parallelFor's share of one worker, or one dp task) leaves one record, its worker as "SM".
// Records are pushed with the same atomic index as on the GPU.
#pragma once

#include <vector>

#include "gvdp/profile/timeline.h"

namespace gvdp::detail {

class CpuTimeline {
 public:
  explicit CpuTimeline(uint32_t capacity) : records_(capacity) {}

  TimelineView view() { return {records_.data(), static_cast<uint32_t>(records_.size()), &count_}; }
  void begin() { count_ = 0; }
  std::vector<TimelineRecord> end(uint64_t* overflow) const {
    uint32_t kept = count_ < records_.size() ? count_ : static_cast<uint32_t>(records_.size());
    *overflow = count_ - kept;
    return {records_.begin(), records_.begin() + kept};
  }

 private:
  std::vector<TimelineRecord> records_;
  uint32_t count_ = 0;
};

// Makes the thread pool record the calling thread's runs into `timeline` (nullptr: stop).
void recordThreadPoolInto(CpuTimeline* timeline);

}  // namespace gvdp::detail
