// The brick cache as one POD view over buffers owned by a backend (docs/STYLE.md 5): indirection
// table (clipmap entries), inverse table, timestamps, free slot list, request queue and the
// counters the schedulers read. Kernels and CPU tasks take it by value.
#pragma once

#include <cstdint>

#include "gvdp/base/atomics.h"
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
  COUNTER_FREE_NEXT,     // next index into the free slot list (may run past its length)
  COUNTER_REQUESTS,      // bricks queued for production (CAS winners)
  COUNTER_PRODUCED,      // bricks written to the pool
  COUNTER_EMPTY,         // bricks found empty
  COUNTER_FAILED,        // productions without a free slot (entry back to MISSING)
  COUNTER_EVICTED,       // resident bricks unmapped (LRU or leaving the clipmap)
  COUNTER_UNSAMPLED,     // at the frame's end: bricks produced in it that no ray sampled
  COUNTER_PREFETCHED,    // at the frame's end: bricks produced in it for the next frame (prefetch)
  COUNTER_DEADLINE = 8,  // 64 bits: the frame's deadline (budgeted)
  COUNTER_PREFETCH_UNUSED = COUNTER_DEADLINE + 2,  // at the frame's end: the last frame's
                                                   // prefetched bricks that no ray of it sampled
  // The free slot list's length (freeListLength), written on the backend by the LRU sort: the
  // host never waits for it at a frame's start.
  COUNTER_FREE_COUNT,
  COUNTER_CLEAR,        // bricks found clear (brick_key.h: ENTRY_CLEAR)
  COUNTER_LISTED,       // bricks listed for a table box (table_boxes.h), EMPTY and CLEAR
  COUNTER_LISTED_LAST,  // the last frame's, whose boxes grow in this one (startFrameCounter)
  COUNTER_GROWN_NEXT,   // of those, the next one a GPU warp takes (launchGrowTableBoxes)
  COUNTER_MARKED,       // bricks marked EMPTY as members of a produced brick's box (produce.h)
  // The march's 64-bit counters (MarchCounter), in a 128-byte line of their own: every warp's
  // march adds to them, and a load of a word in a line under atomics waits behind them (the
  // degraded test's load of COUNTER_FAILED did, on pt's march: ncu, H100).
  COUNTER_MARCH = 32,
  COUNTER_COUNT = COUNTER_MARCH + 2 * MARCH_COUNTER_COUNT
};
static_assert(COUNTER_MARCH % 2 == 0, "the march's 64-bit counters must be 8-byte aligned");
static_assert(COUNTER_MARKED < COUNTER_MARCH, "the cache counters run into the march's");

// A slot's timestamp from its production until a ray samples it is the frame with this bit set;
// the LRU order ignores the bit, and the frame's end counts and clears it (over-production).
// A brick produced for the next frame (pt's idle-time prefetch) is stamped with that frame and
// both bits: the LRU keeps it through the next frame, whose end counts it as used (a ray stamped
// it) or not (over-production).
constexpr uint32_t TIMESTAMP_UNSAMPLED = 0x80000000u, TIMESTAMP_PREFETCHED = 0x40000000u;
constexpr uint32_t TIMESTAMP_MARKS = TIMESTAMP_UNSAMPLED | TIMESTAMP_PREFETCHED;

GVDP_HD GVDP_INLINE uint32_t lastUsedFrame(uint32_t timestamp) {
  return timestamp & ~TIMESTAMP_MARKS;
}

// What a frame's end finds in a slot's timestamp (takeUnsampled).
enum class SlotMark { None, Unsampled, PrefetchUnused, Prefetched };

// Frame end, per slot: Unsampled when its brick was produced in `frame` and never sampled,
// PrefetchUnused when it was prefetched for `frame` and never sampled (both over-production; the
// timestamp becomes the frame), Prefetched when it was prefetched in `frame` for the next one.
GVDP_HD GVDP_INLINE SlotMark takeUnsampled(uint32_t* timestamp, uint32_t frame) {
  uint32_t t = *timestamp;
  if (t == ((frame + 1) | TIMESTAMP_MARKS)) return SlotMark::Prefetched;
  if (t != (frame | TIMESTAMP_UNSAMPLED) && t != (frame | TIMESTAMP_MARKS)) return SlotMark::None;
  *timestamp = frame;
  return t == (frame | TIMESTAMP_UNSAMPLED) ? SlotMark::Unsampled : SlotMark::PrefetchUnused;
}

// A slot's mark into the frame's counters (CacheCounter).
GVDP_HD GVDP_INLINE void countSlotMark(uint32_t* counters, SlotMark m) {
  if (m == SlotMark::None) return;
  if (m == SlotMark::Prefetched) {
    atomicAdd32(&counters[COUNTER_PREFETCHED], 1u);
    return;
  }
  atomicAdd32(&counters[COUNTER_UNSAMPLED], 1u);
  if (m == SlotMark::PrefetchUnused) atomicAdd32(&counters[COUNTER_PREFETCH_UNUSED], 1u);
}

// A ray's costs (CacheView::rayCosts): brick lookups, samples, and stops (marches that ended on
// a brick not ready: the productions the ray waited on, one after the other).
enum RayCostWord : int { RAY_COST_LOOKUPS, RAY_COST_SAMPLES, RAY_COST_STOPS, RAY_COST_WORDS };

// EMPTY and CLEAR bricks listed per frame for their table boxes (table_boxes.h); those beyond keep
// the box they have (a frame from a cold cache publishes more: perlin's first frame at 300x200,
// 235 000 EMPTY bricks; later ones 8 000).
constexpr uint32_t BOX_LIST_CAPACITY = 1u << 18;
constexpr uint32_t BOX_LISTS = 2;  // this frame's list and the last's, used in turn (frame % 2)

struct CacheView {
  Clipmap clipmap;
  uint32_t* entries;          // clipmap.entryCount()
  uint32_t* timestamps;       // per slot: last frame it was sampled (0: never; TIMESTAMP_UNSAMPLED)
  BrickKey* inverse;          // per slot: the brick it holds, level NO_LEVEL if none
  const uint32_t* freeSlots;  // freeCount() valid entries
  BrickKey* requests;         // production queue
  uint32_t requestCapacity;
  BrickKey* listedKeys;  // the frame's EMPTY and CLEAR bricks, as published (table_boxes.h);
                         // in a growth's view, the last frame's
  uint32_t listCapacity;
  uint32_t* counters;         // CacheCounter
  uint32_t frame;             // current frame stamp (>= 1)
  uint32_t degraded;          // nonzero: no production; rays fall back to coarser levels
  uint32_t degradeOnFailure;  // nonzero: a failed production degrades the frame (dp, pt)
  uint32_t budgeted;          // nonzero: the frame has a deadline (a time budget)
  float voxelSize0;
  // Per pixel p of the frame, when it records ray costs (FrameSetup::rayCosts; else null): its
  // ray's brick lookups, samples and stops (RayCostWord), relaunches summed, at
  // RAY_COST_WORDS p + the word.
  uint32_t* rayCosts;

  // Valid entries of freeSlots: written before the kernels that read it (stream order).
  GVDP_HD uint32_t freeCount() const { return counters[COUNTER_FREE_COUNT]; }

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
