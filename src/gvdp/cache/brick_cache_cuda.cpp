#include "gvdp/cache/brick_cache_cuda.h"

#include <numeric>
#include <utility>
#include <vector>

#include "gvdp/cache/cache_kernels.h"
#include "gvdp/cache/lru_order.h"

namespace gvdp::detail {

CudaCacheOps::CudaCacheOps(uint32_t poolBricks, cudaStream_t stream)
    : stream_(stream), order_(poolBricks), next_(poolBricks), tileSizes_(lruTileCount(poolBricks)) {
  std::vector<uint32_t> slots(poolBricks);
  std::iota(slots.begin(), slots.end(), 0u);  // a pool never used, in order
  writeDevice(order_.data(), slots.data(), order_.bytes(), stream_);
  GVDP_CUDA_CHECK(cudaStreamCreateWithFlags(&boxes_, cudaStreamNonBlocking));
  GVDP_CUDA_CHECK(cudaEventCreateWithFlags(&queued_, cudaEventDisableTiming));
  GVDP_CUDA_CHECK(cudaEventCreateWithFlags(&grown_, cudaEventDisableTiming));
}

CudaCacheOps::~CudaCacheOps() {
  cudaStreamSynchronize(boxes_);  // no error thrown from here: the buffers go after it
  cudaEventDestroy(grown_);
  cudaEventDestroy(queued_);
  cudaStreamDestroy(boxes_);
}

void CudaCacheOps::zero(uint32_t* p, size_t n) const {
  fillDevice(p, 0, n * sizeof(uint32_t), stream_);
}

void CudaCacheOps::read(const uint32_t* from, uint32_t* to, size_t n) const {
  readDevice(to, from, n * sizeof(uint32_t), stream_);
}

void CudaCacheOps::resetSlabs(const CacheView& v, const SlabJobs& slabs,
                              const TimelineView& t) const {
  NvtxRange range("cache: clipmap move");
  launchResetSlabs(v, slabs, t, stream_);
}

const uint32_t* CudaCacheOps::buildLruOrder(const uint32_t* timestamps, uint32_t n, uint32_t frame,
                                            uint32_t* counters, const TimelineView& t) {
  NvtxRange range("cache: LRU order");
  launchLruOrder(timestamps, order_.data(), next_.data(), n, builtAt_, frame, tileSizes_.data(),
                 counters, t, stream_);
  std::swap(order_, next_);
  builtAt_ = frame;
  return order_.data();
}

void CudaCacheOps::unmapSlots(const CacheView& v, uint32_t n, const TimelineView& t) const {
  launchUnmapSlots(v, n, t, stream_);
}

void CudaCacheOps::countUnsampled(uint32_t* timestamps, uint32_t n, uint32_t frame,
                                  uint32_t* counters) const {
  launchCountUnsampled(timestamps, n, frame, counters, TimelineView{}, stream_);
}

void CudaCacheOps::settleFresh(const CacheView& v, uint32_t n, const TimelineView& t) const {
  launchSettleFresh(v, n, t, stream_);
}

void CudaCacheOps::tableBoxesReady() const {
  GVDP_CUDA_CHECK(cudaEventRecord(queued_, stream_));
}

void CudaCacheOps::growTableBoxes(const CacheView& v, const TimelineView& t) const {
  GVDP_CUDA_CHECK(cudaStreamWaitEvent(boxes_, queued_));
  launchGrowTableBoxes(v, t, boxes_);
  GVDP_CUDA_CHECK(cudaEventRecord(grown_, boxes_));
}

void CudaCacheOps::joinTableBoxes() const {
  GVDP_CUDA_CHECK(cudaStreamWaitEvent(stream_, grown_));  // none recorded yet: no wait
}

void CudaCacheOps::startFrame(const CacheView& v, uint32_t settle, int64_t deadlineNs,
                              const TimelineView& t) const {
  launchStartFrame(v, settle, deadlineNs, t, stream_);
}

size_t CudaCacheOps::lruBytes() const {
  return order_.bytes() + next_.bytes() + tileSizes_.bytes();
}

}  // namespace gvdp::detail
