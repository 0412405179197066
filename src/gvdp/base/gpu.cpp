#include "gvdp/base/gpu.h"

#include "gvdp/base/error.h"
#include "gvdp/base/watchdog.h"

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
namespace {
void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess) throw Error(std::string(what) + " failed: " + cudaGetErrorString(e));
}
}  // namespace

GpuStream createGpuStream() {
  cudaStream_t s = nullptr;
  check(cudaStreamCreateWithFlags(&s, cudaStreamNonBlocking), "cudaStreamCreateWithFlags");
  return s;
}

void destroyGpuStream(GpuStream stream) {
  cudaStreamDestroy(stream);
}

void copyDeviceAsync(void* dst, const void* src, size_t bytes, GpuStream stream, GpuStream after) {
  check(cudaMemcpyAsync(dst, src, bytes, cudaMemcpyDeviceToDevice, stream), "device image copy");
  cudaEvent_t copied = nullptr;
  check(cudaEventCreateWithFlags(&copied, cudaEventDisableTiming), "cudaEventCreate");
  cudaError_t e = cudaEventRecord(copied, stream);
  if (e == cudaSuccess) e = cudaStreamWaitEvent(after, copied, 0);
  cudaEventDestroy(copied);  // released once the copy is done
  check(e, "ordering the device image copy");
}

PinnedDownload::PinnedDownload(size_t bytes) : bytes_(bytes) {
  try {
    check(cudaMalloc(&device_, bytes), "cudaMalloc (download buffer)");
    check(cudaMallocHost(&host_, bytes), "cudaMallocHost (download buffer)");
    // Waiters sleep rather than spin: several encoder threads wait on downloads at once, and
    // spinning ones took the CPU and the driver from the render thread.
    cudaEvent_t e = nullptr;
    check(cudaEventCreateWithFlags(&e, cudaEventDisableTiming | cudaEventBlockingSync),
          "cudaEventCreate");
    event_ = e;
  } catch (...) {
    cudaFree(device_);
    cudaFreeHost(host_);
    throw;
  }
}

PinnedDownload::~PinnedDownload() {
  cudaEventSynchronize(static_cast<cudaEvent_t>(event_));  // no copy in flight into freed memory
  cudaEventDestroy(static_cast<cudaEvent_t>(event_));
  cudaFreeHost(host_);
  cudaFree(device_);
}

void PinnedDownload::start(GpuStream stream) {
  check(cudaMemcpyAsync(host_, device_, bytes_, cudaMemcpyDeviceToHost, stream), "image download");
  check(cudaEventRecord(static_cast<cudaEvent_t>(event_), stream), "cudaEventRecord");
}

const void* PinnedDownload::wait() {
  WatchedWait wait("an image download");
  check(cudaEventSynchronize(static_cast<cudaEvent_t>(event_)), "image download");
  return host_;
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
GpuStream createGpuStream() {
  throw InputError("backend 'cuda' unavailable: this gvdp was built without CUDA");
}
void destroyGpuStream(GpuStream) {}
void copyDeviceAsync(void*, const void*, size_t, GpuStream, GpuStream) {
  throw InputError("backend 'cuda' unavailable: this gvdp was built without CUDA");
}
PinnedDownload::PinnedDownload(size_t bytes) : bytes_(bytes) {
  throw InputError("backend 'cuda' unavailable: this gvdp was built without CUDA");
}
PinnedDownload::~PinnedDownload() = default;
void PinnedDownload::start(GpuStream) {}
const void* PinnedDownload::wait() {
  return nullptr;
}
#endif

}  // namespace gvdp::detail
