#include "gvdp/cache/brick_cache_cuda.h"

#include <algorithm>
#include <bit>

#include "gvdp/cache/cache_kernels.h"

namespace gvdp::detail {

CudaCacheOps::CudaCacheOps(uint32_t poolBricks)
    : keysIn_(poolBricks),
      keysOut_(poolBricks),
      valuesIn_(poolBricks),
      valuesOut_(poolBricks),
      counts_(2),
      temp_(lruSortTempBytes(poolBricks)) {}

void CudaCacheOps::fillBytes(void* p, size_t bytes, int byte) {
  if (bytes) GVDP_CUDA_CHECK(cudaMemset(p, byte, bytes));
}

void CudaCacheOps::zero(uint32_t* p, size_t n) {
  GVDP_CUDA_CHECK(cudaMemset(p, 0, n * sizeof(uint32_t)));
}

void CudaCacheOps::read(const uint32_t* from, uint32_t* to, size_t n) {
  GVDP_CUDA_CHECK(cudaMemcpy(to, from, n * sizeof(uint32_t), cudaMemcpyDeviceToHost));
}

void CudaCacheOps::resetSlabs(const CacheView& v, const SlabJobs& slabs, const TimelineView& t) {
  NvtxRange range("cache: clipmap move");
  launchResetSlabs(v, slabs, t);
}

const uint32_t* CudaCacheOps::sortLru(const uint32_t* timestamps, uint32_t n, uint32_t frame,
                                      uint32_t counts[2], const TimelineView& t) {
  NvtxRange range("cache: LRU sort");
  launchPrepareLruSort(timestamps, keysIn_.data(), valuesIn_.data(), n, t);
  int endBit = std::max(1, static_cast<int>(std::bit_width(frame)));
  lruSort(temp_.data(), temp_.size(), keysIn_.data(), keysOut_.data(), valuesIn_.data(),
          valuesOut_.data(), n, endBit);
  zero(counts_.data(), 2);
  launchCountOlder(keysOut_.data(), n, 1u, counts_.data(), t);
  launchCountOlder(keysOut_.data(), n, frame, counts_.data() + 1, t);
  read(counts_.data(), counts, 2);
  return valuesOut_.data();
}

void CudaCacheOps::unmapSlots(const CacheView& v, const uint32_t* slots, uint32_t n,
                              const TimelineView& t) {
  launchUnmapSlots(v, slots, n, t);
  GVDP_CUDA_CHECK(cudaGetLastError());
}

size_t CudaCacheOps::lruBytes() const {
  return keysIn_.bytes() + keysOut_.bytes() + valuesIn_.bytes() + valuesOut_.bytes() +
         temp_.bytes();
}

}  // namespace gvdp::detail
