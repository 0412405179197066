// stats.json of a render: {"scene", ..., "memory":{structure: bytes},
// "frames":[{"index","ms","passes","bricks_requested","bricks_produced","bricks_empty",
// "bricks_failed","evictions","pool_occupancy","unfinished_pixels","degraded"}, ...]}.
#pragma once

#include <string>
#include <vector>

#include "gvdp/bench/sequence.h"

namespace gvdp::detail {

std::string statsJson(const SequenceOptions& options, const std::vector<FrameStats>& frames,
                      const MemoryReport& memory);
void writeStatsJson(const std::string& path, const SequenceOptions& options,
                    const std::vector<FrameStats>& frames,
                    const MemoryReport& memory);  // throws InputError if unwritable

}  // namespace gvdp::detail
