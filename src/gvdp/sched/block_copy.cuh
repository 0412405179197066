// A kernel's per-frame context in shared memory. Kernels that cannot take the context as a
// parameter (a graph's parameters are fixed when it is built; dp's device-side launches stay
// small with a pointer) keep it in device memory, and every ray reads it many times: through the
// global pointer those reads cost graph a fifth of its frame rate against sp, whose kernels take
// the context by value (H100 bench, 2026-11-23). Each block copies it once instead.
#pragma once

#include <cstdint>

namespace gvdp::detail {

// Call from every thread of the block, before any thread returns (it synchronises); the copy
// lives as long as the block. One copy per type and kernel.
template <class T>
__device__ inline const T& blockCopy(const T* global) {
  static_assert(sizeof(T) % sizeof(uint32_t) == 0 && alignof(T) <= 16);
  constexpr int WORDS = sizeof(T) / sizeof(uint32_t);
  __shared__ alignas(16) uint32_t words[WORDS];
  const uint32_t* from = reinterpret_cast<const uint32_t*>(global);
  int threads = static_cast<int>(blockDim.x * blockDim.y * blockDim.z);
  int thread =
      static_cast<int>(threadIdx.x + blockDim.x * (threadIdx.y + blockDim.y * threadIdx.z));
  for (int i = thread; i < WORDS; i += threads) words[i] = from[i];
  __syncthreads();
  return *reinterpret_cast<const T*>(words);
}

}  // namespace gvdp::detail
