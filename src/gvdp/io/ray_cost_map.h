// A frame's ray costs (FrameStats::rayCosts; `gvdp render --cost-map`) as people read them: each
// pixel's brick lookups, samples and stops as three heat maps side by side, and their
// distribution. A ray's lookups are the chain of brick decisions it waits on one after the other
// (render/march.h: Marcher::seek; in a GPU warp the longest chain of its rays sets its time), its
// stops the chain of productions it waited on.
#pragma once

#include <cstdint>
#include <string>

#include "gvdp/base/image.h"
#include "gvdp/cache/cache_host.h"

namespace gvdp::detail {

// One measure over a frame's pixels: its mean, quantiles (nearest rank) and largest value, with
// the first pixel that has it.
struct CostQuantiles {
  double mean = 0.0;
  uint32_t p50 = 0, p99 = 0, p999 = 0, max = 0;
  int maxX = 0, maxY = 0;
};

struct RayCostSummary {
  CostQuantiles lookups, samples, stops;
};

RayCostSummary summarizeRayCosts(const RayCosts& c);  // c not empty
std::string rayCostLine(const RayCostSummary& s);     // one line for the console
// Lookups, samples and stops per pixel, left to right, each on a log scale from 0 to its frame's
// largest value (black, purple, red, orange, yellow), with a scale bar and `title` above.
Image rayCostImage(const RayCosts& c, const RayCostSummary& s, const std::string& title);
// The summary of `c` (not empty), its picture written to `path` as a PNG.
RayCostSummary writeRayCostMap(const RayCosts& c, const std::string& title,
                               const std::string& path);

}  // namespace gvdp::detail
