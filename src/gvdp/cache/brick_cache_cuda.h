// The CUDA backend's brick cache: the structures of paper 3.2 in device memory (the pool as in
// render/brick_pool.h), the LRU free-slot list refilled with a CUB radix sort of the timestamps.
// Host code drives it; the bodies are cache_ops.h, launched from cache_kernels.cu.
#pragma once

#include "gvdp/base/cuda_util.h"
#include "gvdp/cache/cache_host.h"
#include "gvdp/render/brick_pool.h"
#include "gvdp/render/frame.h"

namespace gvdp {

class BrickCacheCuda {
 public:
  explicit BrickCacheCuda(uint32_t poolBricks);
  BrickCacheCuda(const BrickCacheCuda&) = delete;
  BrickCacheCuda& operator=(const BrickCacheCuda&) = delete;

  void beginFrame(const FrameSetup& frame);
  uint32_t refill();  // from the slots unused in this frame; returns the slots obtained

  CacheView view() const;
  const BrickPool& pool() const { return pool_; }
  void setDegraded(bool d) { degraded_ = d; }
  bool degraded() const { return degraded_; }
  // Reads the counters back (synchronises the stream).
  void readCounters(uint32_t* out) const;
  void clearRequests();
  CacheStats frameStats();
  MemoryReport memory() const;

 private:
  uint32_t poolBricks_;
  ClipmapTracker tracker_;
  Clipmap clipmap_{};
  DeviceBuffer<uint32_t> entries_, timestamps_, counters_;
  DeviceBuffer<BrickKey> inverse_, requests_;
  DeviceBuffer<uint32_t> sortKeysIn_, sortKeysOut_, sortValuesIn_, sortValuesOut_, freeCount_;
  DeviceBuffer<uint8_t> sortTemp_;
  DeviceBuffer<Rgba8> texels_;
  BrickPool pool_{};
  TimelineView timeline_{};  // the frame's (beginFrame)
  uint32_t freeCountHost_ = 0, frame_ = 0, refills_ = 0;
  uint64_t resident_ = 0;
  bool degraded_ = false;
};

}  // namespace gvdp
