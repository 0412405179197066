#include "gvdp/cache/brick_cache_cuda.h"

#include <algorithm>
#include <bit>

#include "gvdp/cache/cache_kernels.h"

namespace gvdp::detail {

CudaCacheOps::CudaCacheOps(uint32_t poolBricks, cudaStream_t stream)
    : stream_(stream),
      keysIn_(poolBricks),
      keysOut_(poolBricks),
      valuesIn_(poolBricks),
      valuesOut_(poolBricks),
      counts_(2),
      temp_(lruSortTempBytes(poolBricks)) {}

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

const uint32_t* CudaCacheOps::sortLru(const uint32_t* timestamps, uint32_t n, uint32_t frame,
                                      uint32_t* counters, const TimelineView& t) {
  NvtxRange range("cache: LRU sort");
  launchPrepareLruSort(timestamps, keysIn_.data(), valuesIn_.data(), n, t, stream_);
  int endBit = std::max(1, static_cast<int>(std::bit_width(frame)));
  lruSort(temp_.data(), temp_.size(), keysIn_.data(), keysOut_.data(), valuesIn_.data(),
          valuesOut_.data(), n, endBit, stream_);
  zero(counts_.data(), 2);
  launchCountOlder(keysOut_.data(), n, 1u, counts_.data(), t, stream_);
  launchCountOlder(keysOut_.data(), n, frame, counts_.data() + 1, t, stream_);
  launchFreeListLength(counts_.data(), n, counters, stream_);
  return valuesOut_.data();
}

void CudaCacheOps::unmapSlots(const CacheView& v, uint32_t n, const TimelineView& t) const {
  launchUnmapSlots(v, n, t, stream_);
  GVDP_CUDA_CHECK(cudaGetLastError());
}

void CudaCacheOps::countUnsampled(uint32_t* timestamps, uint32_t n, uint32_t frame,
                                  uint32_t* counters) const {
  launchCountUnsampled(timestamps, n, frame, counters, TimelineView{}, stream_);
  GVDP_CUDA_CHECK(cudaGetLastError());
}

void CudaCacheOps::settleFresh(const CacheView& v, uint32_t n, const TimelineView& t) const {
  launchSettleFresh(v, n, t, stream_);
  GVDP_CUDA_CHECK(cudaGetLastError());
}

void CudaCacheOps::setDeadline(uint64_t* at, uint64_t ns) const {
  launchSetDeadline(at, ns, stream_);
  GVDP_CUDA_CHECK(cudaGetLastError());
}

size_t CudaCacheOps::lruBytes() const {
  return keysIn_.bytes() + keysOut_.bytes() + valuesIn_.bytes() + valuesOut_.bytes() +
         temp_.bytes();
}

}  // namespace gvdp::detail
