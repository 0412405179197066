// stats.json of a render: {"scene", ..., "memory":{structure: bytes},
// "frames":[{"index","ms","passes","bricks_requested","bricks_produced","bricks_empty",
// "bricks_clear","bricks_marked_empty","bricks_failed","evictions","pool_occupancy",
// "unfinished_pixels","degraded"},
// ...]}; with ray costs (render --cost-map, one summary per frame) each frame also has
// "ray_costs":{"lookups":
// {"mean","p50","p99","p999","max","max_pixel":[x,y]},"samples":{...},"stops":{...}}.
#pragma once

#include <string>
#include <vector>

#include "gvdp/bench/sequence.h"
#include "gvdp/io/ray_cost_map.h"

namespace gvdp::detail {

std::string statsJson(const SequenceOptions& options, const std::vector<FrameStats>& frames,
                      const MemoryReport& memory, const std::vector<RayCostSummary>& costs = {});
// Throws InputError if unwritable.
void writeStatsJson(const std::string& path, const SequenceOptions& options,
                    const std::vector<FrameStats>& frames, const MemoryReport& memory,
                    const std::vector<RayCostSummary>& costs = {});

}  // namespace gvdp::detail
