// The importance pre-pass (importance.h) run for a frame: the quadtree's shape from the frame's
// size, the hash table sized and grown until the keys fit, the counts back on the host.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "gvdp/base/gpu.h"
#include "gvdp/render/frame.h"
#include "gvdp/sched/importance.h"
#include "gvdp/sched/producer_kernels.h"

namespace gvdp::detail {

struct ImportanceOptions {
  int blockPixels = 16;  // at least: doubled until the blocks fit IMPORTANCE_MAX_LEVELS levels
  int stride = 4;        // pixels between pre-pass rays (a divisor of blockPixels)
  // The first table's entries, a power of two (then 4x per refill); 0: from the rays, about 8
  // keys a ray per quadtree depth, so that a refill is rare.
  uint64_t firstTableEntries = 0;
  uint64_t maxTableBytes = uint64_t{1} << 30;  // the hash table's limit; past it, no map
};

struct ImportanceMap {
  int blocksX = 0, blocksY = 0;  // the frame's blocks
  int levels = 0;                // K: the quadtree covers 2^K x 2^K blocks
  int blockPixels = 0, stride = 0;
  std::vector<uint32_t> counts;   // per node, root first (base/quadtree_layout.h); empty: none
  const char* failure = nullptr;  // why there is none
  uint64_t entries = 0;           // keys inserted (every depth)
  uint64_t tableBytes = 0;
  int attempts = 0;  // passes run (the table grows 4x after one that fills it)
  double ms = 0.0;   // wall clock of the passes, downloads included

  uint32_t root() const { return counts.empty() ? 0u : counts[0]; }
};

// The map's shape for a frame (no counts): blocks, levels, stride; throws InputError for
// options out of range.
ImportanceMap importanceShape(const FrameSetup& frame, const ImportanceOptions& options);

// One pass with a table of `tableEntries` (a power of two) into map.counts; the status words.
using ImportanceStatus = std::array<uint32_t, IMPORTANCE_STATUS_WORDS>;
ImportanceStatus countBricksOnHost(const ProducerKernels& producer, const FrameSetup& frame,
                                   uint64_t tableEntries, ImportanceMap& map);
// The same on the device (CUDA builds; throws InputError in others).
ImportanceStatus countBricksOnDevice(const ProducerKernels& producer, const FrameSetup& frame,
                                     uint64_t tableEntries, GpuStream stream, ImportanceMap& map);

// The setup of a pass over `map`'s shape (pointers filled by the caller's backend).
ImportanceSetup importanceSetup(const ImportanceMap& map, const FrameSetup& frame,
                                uint64_t tableEntries);

}  // namespace gvdp::detail
