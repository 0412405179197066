// The brick cache as one POD view over buffers owned by a backend (docs/STYLE.md 5): indirection
// table (clipmap entries), inverse table, timestamps, free slot list, request queue and the
// counters the schedulers read. Kernels and CPU tasks take it by value.
#pragma once

#include <cstdint>

#include "gvdp/cache/brick_key.h"
#include "gvdp/cache/clipmap.h"

namespace gvdp::detail {

// What rays did with the cache in a frame (CacheStats): samples composited, brick lookups (one
// per brick entered: a resident brick's samples share one), lookups that skipped empty space, and
// rays that showed a coarser level (or nothing) for a brick that was not ready: past the frame's
// budget, or in a degraded frame.
enum MarchCounter : int {
  MARCH_SAMPLES,
  MARCH_LOOKUPS,
  MARCH_SKIPS,
  MARCH_COARSER,
  MARCH_COUNTER_COUNT
};

enum CacheCounter : int {
  COUNTER_FREE_NEXT,  // next index into the free slot list (may run past freeCount)
  COUNTER_REQUESTS,   // bricks queued for production (CAS winners)
  COUNTER_PRODUCED,   // bricks written to the pool
  COUNTER_EMPTY,      // bricks found empty
  COUNTER_FAILED,     // productions without a free slot (entry back to MISSING)
  COUNTER_EVICTED,    // resident bricks unmapped (LRU or leaving the clipmap)
  COUNTER_UNSAMPLED,  // at the frame's end: bricks produced in it that no ray sampled
  COUNTER_MARCH = 8,  // first word of the march's 64-bit counters (MarchCounter), 8-byte aligned
  COUNTER_DEADLINE = COUNTER_MARCH + 2 * MARCH_COUNTER_COUNT,  // 64 bits: the frame's (budgeted)
  COUNTER_COUNT = COUNTER_DEADLINE + 2
};
static_assert(COUNTER_MARCH % 2 == 0, "the march's 64-bit counters must be 8-byte aligned");

// A slot's timestamp from its production until a ray samples it is the frame with this bit set;
// the LRU order ignores the bit, and the frame's end counts and clears it (over-production).
constexpr uint32_t TIMESTAMP_UNSAMPLED = 0x80000000u;

GVDP_HD GVDP_INLINE uint32_t lastUsedFrame(uint32_t timestamp) {
  return timestamp & ~TIMESTAMP_UNSAMPLED;
}

// Frame end, per slot: true when the slot's brick was produced in `frame` and never sampled; its
// timestamp becomes the frame.
GVDP_HD GVDP_INLINE bool takeUnsampled(uint32_t* timestamp, uint32_t frame) {
  if (*timestamp != (frame | TIMESTAMP_UNSAMPLED)) return false;
  *timestamp = frame;
  return true;
}

struct CacheView {
  Clipmap clipmap;
  uint32_t* entries;     // clipmap.entryCount()
  uint32_t* timestamps;  // per slot: last frame it was sampled (0: never; TIMESTAMP_UNSAMPLED)
  BrickKey* inverse;     // per slot: the brick it holds, level NO_LEVEL if none
  const uint32_t* freeSlots;
  uint32_t freeCount;  // valid entries of freeSlots
  BrickKey* requests;  // production queue
  uint32_t requestCapacity;
  uint32_t* counters;         // CacheCounter
  uint32_t frame;             // current frame stamp (>= 1)
  uint32_t degraded;          // nonzero: no production; rays fall back to coarser levels
  uint32_t degradeOnFailure;  // nonzero: a failed production degrades the frame (dp, pt)
  uint32_t budgeted;          // nonzero: the frame has a deadline (a time budget)
  float voxelSize0;

  GVDP_HD uint64_t* marchCounters() const {
    return reinterpret_cast<uint64_t*>(counters + COUNTER_MARCH);
  }
  // A budgeted frame's deadline on clockNanoseconds() of the side the frame runs on, written by
  // the frame's start (BrickCache::beginFrame) before any ray of it.
  GVDP_HD uint64_t* deadline() const {
    return reinterpret_cast<uint64_t*>(counters + COUNTER_DEADLINE);
  }
};

}  // namespace gvdp::detail
