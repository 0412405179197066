// Seek hints: a warp's idle lanes look up the next bricks of a long march at once (GPU; filled by
// render/march_warp.cuh, read by cache/cached_access.h). A march that crosses its bricks one by
// one - a ray grazing the ground over clear cells and small EMPTY boxes, perlin's horizon: 800
// lookups to 80 samples - is a chain of dependent loads, one brick decision a round; in a frame's
// tail its warp is the SM's only one, and each load's latency is the march's. When few of a
// warp's rays are seeking, each of them gets a group of lanes that read, in one round, the
// entries of the bricks under its samples step, step + HINT_SPACING, ... of its level, walking up
// to the first EMPTY ancestor as a lookup does. The ray's own seeks then take the brick decision
// from the hint where one names the brick, and load the entry only where none does.
//
// A hint holds what a lookup would decide on and nothing that changes while a frame runs: a
// resident brick (its slot entry; the lookup still acquires a fresh one before reading the brick)
// or an EMPTY one, its own or its nearest EMPTY ancestor's box (with no resident ancestor between:
// there a degraded frame would stand the ancestor in). A MISSING or in-production brick gives no
// hint. A brick that became resident or EMPTY after its hint named an EMPTY ancestor lies inside
// that ancestor's box, where every sample is zero (world/producer.h): skipping it composites what
// sampling it would, and the image stays the same, bit for bit.
#pragma once

#include <cstdint>

#include "gvdp/base/ray.h"
#include "gvdp/render/lod.h"

namespace gvdp::detail {

constexpr int HINT_SPACING = 4;     // samples between two hints: half a brick's 8 voxels
constexpr int HINT_MIN_LANES = 8;   // lanes a seeking ray gets at least (else no hints)
constexpr uint32_t HINT_AFTER = 8;  // lookups a march makes before it asks for hints
constexpr uint32_t NO_HINT = ~0u;   // SeekHint::index of a hint that names nothing

struct SeekHint {
  uint32_t index;  // the brick's entry (Clipmap::windowEntryOfLocal), NO_HINT: none
  uint32_t entry;  // a slot entry, or an EMPTY entry: the brick's own (up 0) or its ancestor's
  int up;          // levels from the brick to the EMPTY ancestor
};

// The hint that lane `j` of a ray's group reads: the brick under the ray's sample step + j *
// HINT_SPACING of `level` (none past the level's end), as Access::peekHint gives it.
template <class Access>
GVDP_HD SeekHint seekHintOf(const Access& access, const Ray& ray, const Lod& lod, int level,
                            int step, int j) {
  LevelSpan span = lod.span(level);
  float t = span.sampleT(step + j * HINT_SPACING);
  if (t >= span.end) return {NO_HINT, 0u, 0};
  return access.peekHint(level, span.brickOf(ray.o + ray.d * t));
}

}  // namespace gvdp::detail
