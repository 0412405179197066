// stats.json of a render: {"scene", ..., "frames":[{"index","ms","unfinished_pixels"}, ...]}.
#pragma once

#include <string>
#include <vector>

#include "gvdp/bench/sequence.h"

namespace gvdp {

std::string statsJson(const SequenceOptions& options, const std::vector<FrameStats>& frames);
void writeStatsJson(const std::string& path, const SequenceOptions& options,
                    const std::vector<FrameStats>& frames);  // throws InputError if unwritable

}  // namespace gvdp
