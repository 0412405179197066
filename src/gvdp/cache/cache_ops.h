// Cache maintenance bodies shared by the CPU and CUDA backends: resetting the clipmap slabs that
// leave a window, unmapping LRU slots through the inverse table, taking a free slot, publishing
// a produced brick and settling the frame's fresh entries (paper 3.2, 3.3.2, 3.3.4).
#pragma once

#include "gvdp/base/atomics.h"
#include "gvdp/base/clock.h"
#include "gvdp/cache/cache_view.h"

namespace gvdp::detail {

// A slab of one level's window that the camera left: `count` planes along `axis`, starting at
// global brick coordinate `first` (planes of W x W entries each).
struct SlabJob {
  int level, axis, first, count;
};

// All slabs of one frame's window moves, as one launch: job j covers items
// [offset[j], offset[j] + count * W * W).
struct SlabJobs {
  int jobCount;
  SlabJob jobs[3 * MAX_LEVELS];
  uint32_t offset[3 * MAX_LEVELS + 1];
  GVDP_HD uint32_t total() const { return offset[jobCount]; }
};

// Paper 3.3.4: a list of 10% of the pool (small pools may free every slot) ...
GVDP_HD GVDP_INLINE uint32_t freeListCapacity(uint32_t poolBricks) {
  uint32_t tenth = poolBricks / 10;
  uint32_t floor = poolBricks < 256u ? poolBricks : 256u;
  return tenth > floor ? tenth : floor;
}

// ... but never fewer than the slots that hold nothing (a cold pool is free as a whole). The
// list is the head of the slots sorted by timestamp: `unused` slots with timestamp 0 first, then
// `older` - `unused` slots not used in this frame.
GVDP_HD GVDP_INLINE uint32_t freeListLength(uint32_t poolBricks, uint32_t unused, uint32_t older) {
  uint32_t capacity = freeListCapacity(poolBricks);
  uint32_t want = capacity > unused ? capacity : unused;
  return want < older ? want : older;
}

// Frees the slot an entry holds (the slot becomes the least recently used) and resets it.
GVDP_HD GVDP_INLINE void resetEntry(const CacheView& c, uint32_t index) {
  uint32_t e = atomicExch32(&c.entries[index], ENTRY_MISSING);
  if (isSlot(e)) {
    uint32_t slot = slotOf(e);
    c.inverse[slot].level = NO_LEVEL;
    storeRelaxed32(&c.timestamps[slot], 0u);
    atomicAdd32(&c.counters[COUNTER_EVICTED], 1u);
  }
}

GVDP_HD GVDP_INLINE void resetSlabItem(const CacheView& c, const SlabJobs& jobs, uint32_t item) {
  int j = 0;
  while (item >= jobs.offset[j + 1]) ++j;
  const SlabJob& job = jobs.jobs[j];
  uint32_t w = static_cast<uint32_t>(c.clipmap.width);
  uint32_t local = item - jobs.offset[j];
  int plane = job.first + static_cast<int>(local / (w * w));
  int u = static_cast<int>(local % w), v = static_cast<int>((local / w) % w);
  Vec3i g = job.axis == 0   ? Vec3i{plane, u, v}
            : job.axis == 1 ? Vec3i{u, plane, v}
                            : Vec3i{u, v, plane};
  // Only the toroidal index matters: u and v run over every residue of the other two axes.
  resetEntry(c, c.clipmap.entryIndex(job.level, g));
}

// Unmaps the brick a free-list slot still holds (if its entry still points to it). The list is
// taken after settleFresh, so no entry carries ENTRY_FRESH here.
GVDP_HD GVDP_INLINE void unmapSlot(const CacheView& c, uint32_t slot) {
  BrickKey k = c.inverse[slot];
  if (k.level == NO_LEVEL) return;
  uint32_t index = c.clipmap.entryIndex(k.level, k.brick);
  if (atomicCas32(&c.entries[index], slot, ENTRY_MISSING) == slot)
    atomicAdd32(&c.counters[COUNTER_EVICTED], 1u);
  c.inverse[slot].level = NO_LEVEL;
}

// Item i of the free slot list unmapped; run for every i below the pool's size (the list's length
// is on the backend: CacheView::freeCount).
GVDP_HD GVDP_INLINE void unmapFreeSlot(const CacheView& c, uint32_t i) {
  if (i < c.freeCount()) unmapSlot(c, c.freeSlots[i]);
}

// Between frames, item i of the free slot list: the slot's entry loses ENTRY_FRESH if the slot
// was taken (published) in the frame that ended (brick_key.h). Slots are taken from the list in
// order (takeFreeSlot), so the frame's fresh entries are those of its first COUNTER_FREE_NEXT.
GVDP_HD GVDP_INLINE void settleFreshSlot(const CacheView& c, uint32_t i) {
  if (i >= c.freeCount() || i >= c.counters[COUNTER_FREE_NEXT]) return;
  uint32_t slot = c.freeSlots[i];
  BrickKey k = c.inverse[slot];
  if (k.level == NO_LEVEL) return;
  uint32_t* entry = &c.entries[c.clipmap.entryIndex(k.level, k.brick)];
  if (*entry == (slot | ENTRY_FRESH)) *entry = slot;
}

// Counter i at a frame's start: zero, but for the free list's two, which settling reads and the LRU
// order sets (buildLruOrder), and a budgeted frame's deadline (deadlineNs >= 0), set to
// clockNanoseconds() + deadlineNs. Run beside settleFreshSlot, in one pass.
GVDP_HD GVDP_INLINE void startFrameCounter(uint32_t* counters, uint32_t i, int64_t deadlineNs) {
  if (i == COUNTER_FREE_NEXT || i == COUNTER_FREE_COUNT || i == COUNTER_LISTED_LAST) return;
  if (i == COUNTER_LISTED) counters[COUNTER_LISTED_LAST] = counters[COUNTER_LISTED];
  if (deadlineNs >= 0 && (i == COUNTER_DEADLINE || i == COUNTER_DEADLINE + 1)) {
    if (i == COUNTER_DEADLINE)
      *reinterpret_cast<uint64_t*>(counters + i) =
          clockNanoseconds() + static_cast<uint64_t>(deadlineNs);
    return;
  }
  counters[i] = 0;
}

// Queues brick g of `level` for production; the caller won the MISSING -> IN_PRODUCTION CAS on
// `entry`. The queue holds a request per ray of a pass; claims no ray waits for (past a frame's
// deadline) may overflow it: the brick is then MISSING again, for a later pass or frame to claim.
GVDP_HD GVDP_INLINE void requestBrick(const CacheView& c, int level, Vec3i g, uint32_t* entry) {
  uint32_t i = atomicAdd32(&c.counters[COUNTER_REQUESTS], 1u);
  if (i < c.requestCapacity)
    c.requests[i] = {g, level};
  else
    storeRelease32(entry, ENTRY_MISSING);
}

// Algorithm 2, thread 0's part: a slot from the free slot list, or MAX_SLOTS when exhausted.
GVDP_HD GVDP_INLINE uint32_t takeFreeSlot(const CacheView& c) {
  uint32_t i = atomicAdd32(&c.counters[COUNTER_FREE_NEXT], 1u);
  return i < c.freeCount() ? c.freeSlots[i] : MAX_SLOTS;
}

// Algorithm 2, the end: publish what production found, an empty brick (its EMPTY entry,
// brick_key.h: emptyEntry), a clear one (ENTRY_CLEAR), a slot, or MAX_SLOTS when no slot was left.
// EMPTY and CLEAR bricks are listed: their boxes grow from the table in the next frame
// (table_boxes.h). The samples of a resident brick must be written (and fenced, by the caller
// on the GPU) before this.
GVDP_HD GVDP_INLINE void publishBrick(const CacheView& c, const BrickKey& key, uint32_t found) {
  uint32_t index = c.clipmap.entryIndex(key.level, key.brick);
  if (isEmptyEntry(found) || found == ENTRY_CLEAR) {
    storeRelease32(&c.entries[index], found);
    atomicAdd32(&c.counters[found == ENTRY_CLEAR ? COUNTER_CLEAR : COUNTER_EMPTY], 1u);
    uint32_t i = atomicAdd32(&c.counters[COUNTER_LISTED], 1u);
    if (i < c.listCapacity) c.listedKeys[i] = key;
  } else if (found == MAX_SLOTS) {
    storeRelease32(&c.entries[index], ENTRY_MISSING);  // retried after a refill, or degraded
    atomicAdd32(&c.counters[COUNTER_FAILED], 1u);
  } else {
    c.inverse[found] = key;
    storeRelaxed32(&c.timestamps[found], c.frame | TIMESTAMP_UNSAMPLED);  // until a ray samples it
    storeRelease32(&c.entries[index], found | ENTRY_FRESH);
    atomicAdd32(&c.counters[COUNTER_PRODUCED], 1u);
  }
}

// A published brick produced for the next frame (pt's idle-time prefetch), or for the frame
// `ahead` (a far prefetch's last pose): unless a ray of this frame sampled it already, its
// timestamp becomes that frame's with both marks (cache_view.h), which the LRU keeps through that
// frame and whose end counts it as used or not (a ray's stamp before then clears the marks: used).
// A CAS: a ray's stamp of this frame, before or after, wins.
GVDP_HD GVDP_INLINE void markPrefetched(const CacheView& c, const BrickKey& key,
                                        uint32_t ahead = 1) {
  uint32_t e = loadAcquire32(&c.entries[c.clipmap.entryIndex(key.level, key.brick)]);
  if (isSlot(e))
    atomicCas32(&c.timestamps[slotOf(e)], c.frame | TIMESTAMP_UNSAMPLED,
                (c.frame + ahead) | TIMESTAMP_MARKS);
}

}  // namespace gvdp::detail
