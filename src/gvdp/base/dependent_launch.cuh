// Kernels launched one after the other on a stream with Hopper's programmatic dependent launch
// (CUDA programming guide, "Programmatic Dependent Launch and Synchronization"): the GPU may start
// a kernel's blocks before the kernel before it on the stream has finished, and each block waits
// in awaitPriorGrids() until it has - finished and its memory visible, as with plain stream order.
// What it saves is the launch latency between two short kernels, which dominated a frame's start:
// a dozen kernels and memsets of 1-9 us each took 67 us before pt's worker ran (BENCHMARKS.md,
// session 31). A kernel launched so must call awaitPriorGrids() before it touches memory an earlier
// kernel may use; then releaseDependentGrids() lets the next one start its blocks (they wait in
// turn). A kernel that never calls it releases the next one when it ends. A memset or copy between
// two kernels orders them as before.
#pragma once

#include <cuda_runtime.h>

#include <mutex>
#include <unordered_map>
#include <utility>

#include "gvdp/base/cuda_util.h"

namespace gvdp::detail {

// Before the first access to memory an earlier kernel of the stream may touch.
__device__ __forceinline__ void awaitPriorGrids() {
#if defined(__CUDA_ARCH__) && __CUDA_ARCH__ >= 900
  asm volatile("griddepcontrol.wait;" ::: "memory");
#endif
}

// Once every block got here (or ended), the stream's next kernel may start its blocks.
__device__ __forceinline__ void releaseDependentGrids() {
#if defined(__CUDA_ARCH__) && __CUDA_ARCH__ >= 900
  asm volatile("griddepcontrol.launch_dependents;" ::: "memory");
#endif
}

// Whether `kernel` was compiled for compute_90 or later, where awaitPriorGrids waits: code for an
// older architecture (GVDP_CUDA_ARCHITECTURES, or a producer's unit built apart) run on a Hopper
// would honour the launch attribute with no wait in it. Asked once per kernel.
inline bool awaitsPriorGrids(const void* kernel) {
  static std::mutex mutex;
  static std::unordered_map<const void*, bool> known;
  std::lock_guard<std::mutex> lock(mutex);
  auto [at, added] = known.try_emplace(kernel, false);
  if (added) {
    cudaFuncAttributes a{};
    GVDP_CUDA_CHECK(cudaFuncGetAttributes(&a, kernel));
    at->second = a.ptxVersion >= 90;
  }
  return at->second;
}

// kernel<<<grid, block, 0, stream>>>(args...), its blocks free to start before the stream's kernel
// before it ends (the kernel awaits it: awaitPriorGrids); a plain launch for a kernel compiled
// for an older architecture.
template <class... Params, class... Args>
void launchDependent(void (*kernel)(Params...), dim3 grid, dim3 block, cudaStream_t stream,
                     Args&&... args) {
  cudaLaunchAttribute attribute{};
  attribute.id = cudaLaunchAttributeProgrammaticStreamSerialization;
  attribute.val.programmaticStreamSerializationAllowed = 1;
  cudaLaunchConfig_t config{};
  config.gridDim = grid;
  config.blockDim = block;
  config.stream = stream;
  config.attrs = &attribute;
  config.numAttrs = awaitsPriorGrids(reinterpret_cast<const void*>(kernel)) ? 1 : 0;
  GVDP_CUDA_CHECK(cudaLaunchKernelEx(&config, kernel, std::forward<Args>(args)...));
}

}  // namespace gvdp::detail
