// Host-side bookkeeping shared by the CPU and CUDA caches: the clipmap from frame to frame,
// per-frame statistics and the memory report.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "gvdp/cache/slabs.h"

namespace gvdp::detail {

struct CacheStats {
  uint64_t requested = 0, produced = 0, empty = 0, failed = 0, evicted = 0;
  uint64_t clear = 0;       // bricks produced all zero, without a slot (brick_key.h: ENTRY_CLEAR)
  uint64_t marked = 0;      // bricks marked EMPTY, unproduced, in a produced brick's box
  uint64_t resident = 0;    // slots holding a brick at the end of the frame
  uint64_t unsampled = 0;   // bricks produced in the frame that no ray sampled (over-production)
  uint64_t prefetched = 0;  // bricks produced in the frame for the next one (pt's prefetch)
  uint64_t prefetchUnused = 0;  // the last frame's prefetched bricks no ray sampled (in unsampled)
  uint32_t refills = 0;         // free-list refills after the frame-start one
  // What the rays did (MarchCounter): samples, brick lookups, lookups that skipped empty space,
  // rays (pixels) that showed a coarser level for a brick that was not ready.
  uint64_t samples = 0, lookups = 0, skips = 0, coarser = 0;
};

// Each pixel's brick lookups, samples and stops in a frame (FrameSetup::rayCosts), row by row;
// empty when the frame did not record them. The lookups are the chain of brick decisions a ray
// waits on one after the other (render/march.h: Marcher::seek), the stops the chain of
// productions (its marches that ended on a brick not ready); a relaunched ray's marches are
// summed. A tiled frame's are those of the renders its image shows (not of attempts replaced).
struct RayCosts {
  int width = 0, height = 0;
  std::vector<uint32_t> lookups, samples, stops;

  bool empty() const { return lookups.empty(); }
};

struct MemoryItem {
  std::string name;
  size_t bytes;
};
using MemoryReport = std::vector<MemoryItem>;

// A frame's statistics from its counters (CacheCounter), on either backend.
inline CacheStats cacheStatsFrom(const uint32_t* counters, uint64_t resident, uint32_t refills) {
  CacheStats s;
  s.produced = counters[COUNTER_PRODUCED];
  s.empty = counters[COUNTER_EMPTY];
  s.failed = counters[COUNTER_FAILED];
  s.clear = counters[COUNTER_CLEAR];
  s.marked = counters[COUNTER_MARKED];
  s.evicted = counters[COUNTER_EVICTED];
  s.unsampled = counters[COUNTER_UNSAMPLED];
  s.prefetched = counters[COUNTER_PREFETCHED];
  s.prefetchUnused = counters[COUNTER_PREFETCH_UNUSED];
  s.requested = s.produced + s.empty + s.clear + s.failed;  // every request ends in one of them
  s.resident = resident;
  s.refills = refills;
  uint64_t march[MARCH_COUNTER_COUNT];
  std::memcpy(march, counters + COUNTER_MARCH, sizeof march);
  s.samples = march[MARCH_SAMPLES];
  s.lookups = march[MARCH_LOOKUPS];
  s.skips = march[MARCH_SKIPS];
  s.coarser = march[MARCH_COARSER];
  return s;
}

// The clipmap of consecutive frames: the slabs to reset, or a full reset when the geometry
// changed (first frame, other resolution or level count).
class ClipmapTracker {
 public:
  struct Update {
    Clipmap clipmap;
    bool fullReset;
    SlabJobs slabs;
  };

  Update next(const FrameSetup& frame) {
    Update u{clipmapOf(frame), true, {}};
    if (previous_ && previous_->width == u.clipmap.width && previous_->levels == u.clipmap.levels) {
      u.fullReset = false;
      u.slabs = slabJobs(*previous_, u.clipmap);
    }
    previous_ = u.clipmap;
    return u;
  }

 private:
  std::optional<Clipmap> previous_;
};

}  // namespace gvdp::detail
