// Cooperation scopes, as CUB's thread / warp / block: a group that shares a piece of work. Each
// member has a rank in [0, size); the group can AND a flag, OR a word, broadcast its leader's
// word (rank 0) and synchronise. The same algorithm body, templated on the scope, runs as one CPU
// task (ThreadScope), a warp or a block (CUDA code only).
#pragma once

#include <cstdint>

#include "gvdp/base/defs.h"

namespace gvdp::detail {

// One thread does the whole work (a CPU task, or a lone GPU thread).
struct ThreadScope {
  GVDP_HD int rank() const { return 0; }
  GVDP_HD int size() const { return 1; }
  GVDP_HD bool all(bool v) const { return v; }
  GVDP_HD uint32_t any(uint32_t bits) const { return bits; }
  GVDP_HD uint32_t broadcast(uint32_t v) const { return v; }
  GVDP_HD void sync() const {}
};

#if defined(__CUDACC__)
// The 32 lanes of a converged warp.
struct WarpScope {
  int lane;
  __device__ int rank() const { return lane; }
  __device__ int size() const { return 32; }
  __device__ bool all(bool v) const { return __all_sync(0xffffffffu, v); }
  __device__ uint32_t any(uint32_t bits) const { return __reduce_or_sync(0xffffffffu, bits); }
  __device__ uint32_t broadcast(uint32_t v) const { return __shfl_sync(0xffffffffu, v, 0); }
  __device__ void sync() const { __syncwarp(); }
};

// Every thread of the block; `word` is caller-owned shared memory for broadcast() and any().
struct BlockScope {
  uint32_t* word;
  __device__ int rank() const { return static_cast<int>(threadIdx.x); }
  __device__ int size() const { return static_cast<int>(blockDim.x); }
  __device__ bool all(bool v) const { return __syncthreads_and(v) != 0; }
  // The OR of every thread's bits: per warp by shuffle, then one shared atomic per warp.
  __device__ uint32_t any(uint32_t bits) const {
    bits = __reduce_or_sync(0xffffffffu, bits);
    if (threadIdx.x == 0) *word = 0u;
    __syncthreads();
    if ((threadIdx.x & 31u) == 0u) atomicOr(word, bits);
    __syncthreads();
    uint32_t r = *word;
    __syncthreads();  // every thread has read the word before it can be written again
    return r;
  }
  __device__ uint32_t broadcast(uint32_t v) const {
    if (threadIdx.x == 0) *word = v;
    __syncthreads();
    uint32_t r = *word;
    __syncthreads();  // every thread has read the word before it can be written again
    return r;
  }
  __device__ void sync() const { __syncthreads(); }
};
#endif

}  // namespace gvdp::detail
