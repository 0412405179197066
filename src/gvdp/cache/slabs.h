// Host side of the clipmap update: which slabs of which levels the camera left since the last
// frame (docs/DESIGN.md: "the slabs that leave a level are reset to MISSING and their slots
// returned").
#pragma once

#include <cstdlib>

#include "gvdp/cache/cache_ops.h"

namespace gvdp::detail {

// Slabs to reset when the windows move from `before` to `now` (same width and levels). A move of
// W or more along an axis resets the whole level (as one slab of W planes).
inline SlabJobs slabJobs(const Clipmap& before, const Clipmap& now) {
  SlabJobs jobs{};
  int w = now.width;
  uint32_t plane = static_cast<uint32_t>(w) * static_cast<uint32_t>(w);
  for (int level = 0; level < now.levels; ++level) {
    Vec3i a = before.windowOrigin[level], b = now.windowOrigin[level];
    int d[3] = {b.x - a.x, b.y - a.y, b.z - a.z};
    int from[3] = {a.x, a.y, a.z};
    for (int axis = 0; axis < 3; ++axis) {
      if (d[axis] == 0) continue;
      SlabJob job{level, axis, 0, std::min(std::abs(d[axis]), w)};
      job.first = d[axis] > 0 ? from[axis] : from[axis] + w - job.count;
      jobs.offset[jobs.jobCount + 1] = jobs.offset[jobs.jobCount] + job.count * plane;
      jobs.jobs[jobs.jobCount++] = job;
      if (job.count == w) break;  // the whole level is reset
    }
  }
  return jobs;
}

}  // namespace gvdp::detail
