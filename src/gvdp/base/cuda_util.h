// CUDA helpers for host code of the CUDA backend: error checks that throw with file:line, one
// RAII owner of device memory (docs/STYLE.md 5), copies ordered on a stream (the library's work
// runs on each scheduler's own stream, never the default one). Included only by CUDA-enabled
// sources.
#pragma once

#include <cuda_runtime_api.h>
#include <nvtx3/nvToolsExt.h>

#include <cstddef>
#include <utility>

#include "gvdp/base/error.h"
#include "gvdp/base/watchdog.h"

#define GVDP_CUDA_CHECK(call)                                                              \
  do {                                                                                     \
    cudaError_t gvdpErr_ = (call);                                                         \
    if (gvdpErr_ != cudaSuccess)                                                           \
      throw ::gvdp::Error(::gvdp::detail::concat(                                          \
          __FILE__, ":", __LINE__, ": " #call " failed: ", cudaGetErrorString(gvdpErr_))); \
  } while (0)

namespace gvdp::detail {

template <class T>
class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  explicit DeviceBuffer(size_t count) : count_(count) {
    if (count) GVDP_CUDA_CHECK(cudaMalloc(reinterpret_cast<void**>(&ptr_), count * sizeof(T)));
  }
  ~DeviceBuffer() {
    if (ptr_) cudaFree(ptr_);
  }
  DeviceBuffer(DeviceBuffer&& o) noexcept
      : ptr_(std::exchange(o.ptr_, nullptr)), count_(std::exchange(o.count_, 0)) {}
  DeviceBuffer& operator=(DeviceBuffer&& o) noexcept {
    std::swap(ptr_, o.ptr_);
    std::swap(count_, o.count_);
    return *this;
  }
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;

  T* data() const { return ptr_; }
  size_t size() const { return count_; }
  size_t bytes() const { return count_ * sizeof(T); }

 private:
  T* ptr_ = nullptr;
  size_t count_ = 0;
};

// Device memory to the host after the work queued on `stream`: returns when the bytes are there.
// The wait is watched from the copy's call on: into pageable memory (`to` is, mostly) the copy
// itself waits for the stream's work.
inline void readDevice(void* to, const void* from, size_t bytes, cudaStream_t stream) {
  WatchedWait wait("a copy to the host");
  GVDP_CUDA_CHECK(cudaMemcpyAsync(to, from, bytes, cudaMemcpyDeviceToHost, stream));
  GVDP_CUDA_CHECK(cudaStreamSynchronize(stream));
}

// Host memory to the device, ordered on `stream`; `from` may go once this returns (CUDA stages
// pageable memory before cudaMemcpyAsync returns).
inline void writeDevice(void* to, const void* from, size_t bytes, cudaStream_t stream) {
  GVDP_CUDA_CHECK(cudaMemcpyAsync(to, from, bytes, cudaMemcpyHostToDevice, stream));
}

inline void fillDevice(void* to, int byte, size_t bytes, cudaStream_t stream) {
  if (bytes) GVDP_CUDA_CHECK(cudaMemsetAsync(to, byte, bytes, stream));
}

// An NVTX range (Nsight Systems shows the frame's phases), for the lifetime of the object; also
// the watchdog's phase (base/watchdog.h). `name` outlives it (a literal).
class NvtxRange {
 public:
  explicit NvtxRange(const char* name) : phase_(name) { nvtxRangePushA(name); }
  ~NvtxRange() { nvtxRangePop(); }
  NvtxRange(const NvtxRange&) = delete;
  NvtxRange& operator=(const NvtxRange&) = delete;

 private:
  WatchPhase phase_;
};

// CUDA events timing a region of a stream, in milliseconds.
class GpuTimer {
 public:
  GpuTimer() {
    GVDP_CUDA_CHECK(cudaEventCreate(&start_));
    GVDP_CUDA_CHECK(cudaEventCreate(&stop_));
  }
  ~GpuTimer() {
    cudaEventDestroy(start_);
    cudaEventDestroy(stop_);
  }
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;
  void start(cudaStream_t s) { GVDP_CUDA_CHECK(cudaEventRecord(start_, s)); }
  void stop(cudaStream_t s) { GVDP_CUDA_CHECK(cudaEventRecord(stop_, s)); }
  float ms() {
    WatchedWait wait("the end of the timed work");
    GVDP_CUDA_CHECK(cudaEventSynchronize(stop_));
    float ms = 0.0f;
    GVDP_CUDA_CHECK(cudaEventElapsedTime(&ms, start_, stop_));
    return ms;
  }

 private:
  cudaEvent_t start_{}, stop_{};
};

// The current device's SMs.
inline int smCount() {
  int device = 0, sms = 0;
  GVDP_CUDA_CHECK(cudaGetDevice(&device));
  GVDP_CUDA_CHECK(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, device));
  return sms;
}

// Blocks of `kernel` (`threads` each) that fit on the device at once: the grid of a persistent
// or grid-claiming kernel.
template <class Kernel>
int residentBlocks(Kernel kernel, int threads) {
  int perSm = 0;
  GVDP_CUDA_CHECK(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&perSm, kernel, threads, 0));
  return smCount() * (perSm > 0 ? perSm : 1);
}

}  // namespace gvdp::detail
