// The brick cache's host side (paper 3.2), written once over a backend's buffers and operations:
// the clipmap from frame to frame, the indirection and inverse tables, timestamps, the LRU free
// slot list, the request queue and the counters, with the bodies of cache_ops.h run by the
// backend. Ops (HostCacheOps: brick_cache_cpu.h; CudaCacheOps: brick_cache_cuda.h) supplies
//   template <class T> using Buffer             owning array: data(), size(), Buffer<T>(n)
//   fillBytes(Buffer<T>&, int byte)             every byte set (memset)
//   zero(uint32_t* p, size_t n), read(const uint32_t* from, uint32_t* to, size_t n)
//   resetSlabs(view, slabs, timeline)           the slabs the clipmap windows left (cache_ops.h)
//   buildLruOrder(timestamps, n, frame, counters, timeline) -> const uint32_t*   the slots by
//                                               last-used frame, oldest first (lru_order.h, from
//                                               the order it built before); the free list's
//                                               length into counters[COUNTER_FREE_COUNT]
//                                               (lruFreeListLength) and 0 into
//                                               counters[COUNTER_FREE_NEXT], on the backend
//   countUnsampled(timestamps, n, frame, counters)  the slots' marks at the end of `frame`
//                                               counted and cleared (takeUnsampled, countSlotMark)
//   startFrame(view, settle, deadlineNs, timeline)  settleFreshSlot(view, i) for i < settle and
//                                               startFrameCounter(view.counters, i, deadlineNs)
//                                               for every counter, in one pass (cache_ops.h)
//   unmapSlots(view, n, timeline)               unmapFreeSlot(view, i) for i < n (cache_ops.h)
//   settleFresh(view, n, timeline)              settleFreshSlot(view, i) for i < n (cache_ops.h)
//   growTableBoxes(view, timeline)              growTableBox(group, view, i) for the listed
//                                               items (table_boxes.h: listedItems), maybe
//                                               while the frame's kernels run
//   tableBoxesReady()                           marks the frame's start done: a growth may begin
//   joinTableBoxes()                            waits (the backend's stream does) for them
//   lruBytes(), LRU_NAME                        what the LRU order holds, for the memory report
#pragma once

#include <cstdint>

#include "gvdp/base/error.h"
#include "gvdp/cache/cache_host.h"
#include "gvdp/render/brick_pool.h"
#include "gvdp/render/frame.h"
#include "gvdp/world/voxel.h"

namespace gvdp::detail {

template <class Ops>
class BrickCache {
 public:
  template <class T>
  using Buffer = typename Ops::template Buffer<T>;

  // `opsArgs` follow the pool size to the Ops' constructor (CudaCacheOps: the stream).
  template <class... OpsArgs>
  explicit BrickCache(uint32_t poolBricks, OpsArgs... opsArgs)
      : poolBricks_(poolBricks),
        timestamps_(poolBricks),
        counters_(COUNTER_COUNT),
        inverse_(poolBricks),
        ops_(poolBricks, opsArgs...) {
    GVDP_INPUT_CHECK(poolBricks >= 1 && poolBricks < SLOT_LIMIT, "bad --pool-bricks ", poolBricks);
    texels_ = Buffer<Rgba8>(static_cast<size_t>(poolBricks) * BRICK_SAMPLE_COUNT);
    occupancy_ = Buffer<uint64_t>(poolBricks);
    for (auto& list : listedKeys_) list = Buffer<BrickKey>(BOX_LIST_CAPACITY);
  }
  BrickCache(const BrickCache&) = delete;
  BrickCache& operator=(const BrickCache&) = delete;

  // A frame-time budget from now on (ns from each frame's start; negative: none, the default).
  // Past it, a ray whose brick is not ready shows the nearest resident coarser level instead of
  // waiting (CachedAccess::find); the brick is still produced, for the next frames.
  void setBudget(int64_t ns) { budgetNs_ = ns; }
  bool budgeted() const { return budgetNs_ >= 0; }

  // Frame start: the deadline (budgeted), move the clipmap windows (reset the slabs left, or
  // everything when the geometry changed or the frame asks for a cold cache), stamp the frame, size
  // the request queue, refill the free slot list.
  void beginFrame(const FrameSetup& frame) {
    timeline_ = frame.timeline;  // the last frame's may be gone
    ops_.joinTableBoxes();       // the last growth's stores land before the table changes
    // The last frame's fresh marks settled, the counters zeroed and the deadline set: one pass.
    ops_.startFrame(view(), freeSlots_ ? poolBricks_ : 0u, budgeted() ? budgetNs_ : int64_t{-1},
                    timeline_);
    ClipmapTracker::Update u = tracker_.next(frame);
    clipmap_ = u.clipmap;
    degraded_ = false;
    ++frame_;
    startedEmpty_ = u.fullReset || frame.coldCache;
    if (startedEmpty_) {
      if (entries_.size() != clipmap_.entryCount())
        entries_ = Buffer<uint32_t>(clipmap_.entryCount());
      ops_.fillBytes(entries_, 0xff);  // ENTRY_MISSING
      ops_.fillBytes(timestamps_, 0);  // never used
      ops_.fillBytes(inverse_, 0xff);  // level NO_LEVEL
      resident_ = 0;
    } else {
      ops_.resetSlabs(view(), u.slabs, timeline_);
    }
    size_t rays = static_cast<size_t>(frame.pixelCount());
    if (requests_.size() < rays) requests_ = Buffer<BrickKey>(rays);
    costWidth_ = frame.rayCosts ? frame.width : 0;
    costHeight_ = frame.height;
    if (frame.rayCosts) {
      if (rayCosts_.size() != RAY_COST_WORDS * rays)
        rayCosts_ = Buffer<uint32_t>(RAY_COST_WORDS * rays);
      ops_.fillBytes(rayCosts_, 0);
    }
    takeFreeList();
    refills_ = 0;
    ops_.tableBoxesReady();
    if (!deferTableBoxes_) growTableBoxes();
  }

  // The last frame's EMPTY and CLEAR bricks grow their boxes, in this frame's clipmap, after its
  // start, while its rays run (a CUDA cache's on a stream of its own): they read what the table
  // knows, which only grows while a frame runs, and store over entries nothing else writes in it.
  // In beginFrame, unless the scheduler calls it itself after its frame's kernels are queued
  // (deferTableBoxes: pt, whose persistent kernel should find the SMs free).
  void growTableBoxes() {
    if (frame_ <= 1) return;
    CacheView last = view();
    last.listedKeys = listedKeys_[(frame_ + 1) % BOX_LISTS].data();
    ops_.growTableBoxes(last, timeline_);
  }
  void deferTableBoxes() { deferTableBoxes_ = true; }

  // Mid-frame refill (paper 3.3.4) from the slots not used in this frame, least recently used
  // first; returns the slots obtained. Only between kernels (the fresh marks are settled).
  uint32_t refill() {
    settleFresh();
    takeFreeList();
    uint32_t count = 0;
    ops_.read(counters_.data() + COUNTER_FREE_COUNT, &count, 1);
    return count;
  }

  // The fresh marks (brick_key.h: ENTRY_FRESH) of the bricks published since the free list was
  // taken, cleared: each took its slot from the list, in order. Between a frame's kernels and the
  // next's (beginFrame), or before a mid-frame refill replaces the list.
  void settleFresh() {
    if (freeSlots_) ops_.settleFresh(view(), poolBricks_, timeline_);
  }

  CacheView view() {
    CacheView v{};
    v.clipmap = clipmap_;
    v.entries = entries_.data();
    v.timestamps = timestamps_.data();
    v.inverse = inverse_.data();
    v.freeSlots = freeSlots_;
    v.requests = requests_.data();
    v.requestCapacity = static_cast<uint32_t>(requests_.size());
    v.listedKeys = listedKeys_[frame_ % BOX_LISTS].data();  // this frame's; the other: the last's
    v.listCapacity = BOX_LIST_CAPACITY;
    v.counters = counters_.data();
    v.frame = frame_;
    v.degraded = degraded_ ? 1u : 0u;
    v.budgeted = budgeted() ? 1u : 0u;
    v.rayCosts = costWidth_ ? rayCosts_.data() : nullptr;
    return v;
  }
  BrickPool pool() { return BrickPool{texels_.data(), occupancy_.data()}; }

  // The counters (CacheCounter) as they are now (on the GPU: synchronises).
  void readCounters(uint32_t* out) const { ops_.read(counters_.data(), out, COUNTER_COUNT); }
  void clearRequests() { ops_.zero(counters_.data() + COUNTER_REQUESTS, 1); }
  const BrickKey* requests() const { return requests_.data(); }
  // Whether the frame began with every entry MISSING (its first, a cold or a reset clipmap).
  bool startedEmpty() const { return startedEmpty_; }
  void setDegraded(bool d) { degraded_ = d; }
  bool degraded() const { return degraded_; }

  // The frame's statistics (once, at its end); the resident count follows from the counters.
  CacheStats frameStats() {
    ops_.countUnsampled(timestamps_.data(), poolBricks_, frame_, counters_.data());
    uint32_t c[COUNTER_COUNT];
    readCounters(c);
    resident_ = resident_ + c[COUNTER_PRODUCED] - c[COUNTER_EVICTED];
    return cacheStatsFrom(c, resident_, refills_);
  }

  // The frame's ray costs, when it records them (FrameSetup::rayCosts; else empty).
  RayCosts rayCosts() const {
    RayCosts c;
    if (!costWidth_) return c;
    size_t n = static_cast<size_t>(costWidth_) * costHeight_;
    std::vector<uint32_t> words(RAY_COST_WORDS * n);
    ops_.read(rayCosts_.data(), words.data(), words.size());
    c.width = costWidth_;
    c.height = costHeight_;
    c.lookups.resize(n);
    c.samples.resize(n);
    c.stops.resize(n);
    for (size_t p = 0; p < n; ++p) {
      c.lookups[p] = words[RAY_COST_WORDS * p + RAY_COST_LOOKUPS];
      c.samples[p] = words[RAY_COST_WORDS * p + RAY_COST_SAMPLES];
      c.stops[p] = words[RAY_COST_WORDS * p + RAY_COST_STOPS];
    }
    return c;
  }

  MemoryReport memory() const {
    MemoryReport m{{"brick_pool", bytesOf(texels_)},
                   {"brick_occupancy", bytesOf(occupancy_)},
                   {"indirection_table", bytesOf(entries_)},
                   {"inverse_table", bytesOf(inverse_)},
                   {"timestamps", bytesOf(timestamps_)},
                   {Ops::LRU_NAME, ops_.lruBytes()},
                   {"request_queue", bytesOf(requests_)},
                   {"box_lists", BOX_LISTS * bytesOf(listedKeys_[0])}};
    if (rayCosts_.size()) m.push_back({"ray_costs", bytesOf(rayCosts_)});  // render --cost-map
    return m;
  }

  // The raw tables, in the backend's memory (tests read the CPU ones).
  uint32_t poolBricks() const { return poolBricks_; }
  const Clipmap& clipmap() const { return clipmap_; }
  const Buffer<uint32_t>& entries() const { return entries_; }
  const Buffer<BrickKey>& inverse() const { return inverse_; }
  const Buffer<uint32_t>& timestamps() const { return timestamps_; }
  const Buffer<Rgba8>& texels() const { return texels_; }

 private:
  // The free slot list from the LRU order, its slots unmapped. Its length stays on the backend
  // (COUNTER_FREE_COUNT): the kernels that follow read it there, and the host does not wait for
  // the order (H100: pt's first render task came 194 -> 134 us into perlin's frame 12).
  void takeFreeList() {
    freeSlots_ =
        ops_.buildLruOrder(timestamps_.data(), poolBricks_, frame_, counters_.data(), timeline_);
    ops_.unmapSlots(view(), poolBricks_, timeline_);
    ++refills_;
  }

  template <class T>
  static size_t bytesOf(const Buffer<T>& b) {
    return b.size() * sizeof(T);
  }

  uint32_t poolBricks_;
  ClipmapTracker tracker_;
  Clipmap clipmap_{};
  Buffer<uint32_t> entries_, timestamps_, counters_, rayCosts_;
  bool deferTableBoxes_ = false;
  Buffer<BrickKey> inverse_, requests_, listedKeys_[BOX_LISTS];
  Buffer<Rgba8> texels_;
  Buffer<uint64_t> occupancy_;
  Ops ops_;
  TimelineView timeline_{};  // the frame's (beginFrame)
  const uint32_t* freeSlots_ = nullptr;
  uint32_t frame_ = 0, refills_ = 0;
  int costWidth_ = 0, costHeight_ = 0;  // the frame's, when it records ray costs (else 0)
  uint64_t resident_ = 0;
  bool startedEmpty_ = false;
  int64_t budgetNs_ = -1;
  bool degraded_ = false;
};

}  // namespace gvdp::detail
