#include "gvdp/base/gpu.h"

#include "gvdp/base/error.h"

#if GVDP_HAS_CUDA
#include <cuda_runtime_api.h>
#endif

#include <sstream>

namespace gvdp::detail {

#if GVDP_HAS_CUDA
bool cudaBuilt() {
  return true;
}

bool cudaDeviceAvailable() {
  int count = 0;
  return cudaGetDeviceCount(&count) == cudaSuccess && count > 0;
}

std::string cudaDeviceSummary() {
  int count = 0;
  cudaError_t e = cudaGetDeviceCount(&count);
  if (e != cudaSuccess) return std::string("no CUDA device (") + cudaGetErrorString(e) + ")";
  std::ostringstream s;
  for (int i = 0; i < count; ++i) {
    cudaDeviceProp p{};
    cudaGetDeviceProperties(&p, i);
    s << (i ? "\n" : "") << "cuda:" << i << " " << p.name << ", sm_" << p.major << p.minor << ", "
      << p.multiProcessorCount << " SMs, " << (p.totalGlobalMem >> 20) << " MiB";
  }
  return s.str();
}

std::optional<uint64_t> cudaFreeMemoryBytes() {
  size_t freeBytes = 0, totalBytes = 0;
  if (!cudaDeviceAvailable() || cudaMemGetInfo(&freeBytes, &totalBytes) != cudaSuccess)
    return std::nullopt;
  return freeBytes;
}
void copyDeviceAsync(void* dst, const void* src, size_t bytes, void* stream) {
  cudaError_t e =
      cudaMemcpyAsync(dst, src, bytes, cudaMemcpyDeviceToDevice, static_cast<cudaStream_t>(stream));
  if (e != cudaSuccess)
    throw Error(std::string("device image copy failed: ") + cudaGetErrorString(e));
}
#else
bool cudaBuilt() {
  return false;
}
bool cudaDeviceAvailable() {
  return false;
}
std::string cudaDeviceSummary() {
  return "this gvdp was built without CUDA";
}
std::optional<uint64_t> cudaFreeMemoryBytes() {
  return std::nullopt;
}
void copyDeviceAsync(void*, const void*, size_t, void*) {
  throw InputError("backend 'cuda' unavailable: this gvdp was built without CUDA");
}
#endif

}  // namespace gvdp::detail
