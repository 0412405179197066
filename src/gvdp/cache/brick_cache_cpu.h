// The CPU backend's brick cache: the structures of paper 3.2 in host memory, with the same
// bodies (cache_ops.h) run on the thread pool.
#pragma once

#include <algorithm>

#include <vector>

#include "gvdp/cache/cache_host.h"
#include "gvdp/render/brick_pool.h"
#include "gvdp/render/frame.h"
#include "gvdp/world/voxel.h"

namespace gvdp {

class BrickCacheCpu {
 public:
  explicit BrickCacheCpu(uint32_t poolBricks);

  // Frame start: move the clipmap windows (reset the slabs left), stamp the frame, refill the
  // free slot list from the least recently used slots, size the request queue for the frame.
  void beginFrame(const FrameSetup& frame);
  // Mid-frame refill from the slots not used in this frame; returns the slots obtained.
  uint32_t refill();

  CacheView view();
  BrickPool pool() { return BrickPool{texels_.data()}; }
  const uint32_t* counters() const { return counters_; }
  void readCounters(uint32_t* out) const { std::copy_n(counters_, COUNTER_COUNT, out); }
  void setDegraded(bool d) { degraded_ = d; }
  bool degraded() const { return degraded_; }
  void clearRequests() { counters_[COUNTER_REQUESTS] = 0; }
  const BrickKey* requests() const { return requests_.data(); }

  Rgba8* texels() { return texels_.data(); }
  uint32_t poolBricks() const { return poolBricks_; }
  CacheStats frameStats() const;
  MemoryReport memory() const;

  // For tests: the raw tables.
  const std::vector<uint32_t>& entries() const { return entries_; }
  const std::vector<BrickKey>& inverse() const { return inverse_; }
  const std::vector<uint32_t>& timestamps() const { return timestamps_; }
  const Clipmap& clipmap() const { return clipmap_; }

 private:
  uint32_t poolBricks_;
  ClipmapTracker tracker_;
  Clipmap clipmap_{};
  std::vector<uint32_t> entries_, timestamps_, freeSlots_;
  std::vector<BrickKey> inverse_, requests_;
  std::vector<Rgba8> texels_;
  uint32_t counters_[COUNTER_COUNT] = {};
  uint32_t freeCount_ = 0, frame_ = 0, refills_ = 0;
  bool degraded_ = false;
};

}  // namespace gvdp
