// What the host knows about the GPU without including CUDA headers: whether this build has the
// CUDA backend and whether a device is present at run time (GPU tests skip when not).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

struct CUstream_st;  // cudaStream_t is CUstream_st*

namespace gvdp::detail {

using GpuStream = CUstream_st*;

bool cudaBuilt();
bool cudaDeviceAvailable();
// One line per device (name, SMs, memory), or why there is none.
std::string cudaDeviceSummary();
// Free memory of the current device (cudaMemGetInfo); nullopt without a device.
std::optional<uint64_t> cudaFreeMemoryBytes();
// A stream of the library's own (non-blocking: it never waits for the legacy default stream);
// its handle is a cudaStream_t. Throws in builds without CUDA.
GpuStream createGpuStream();
void destroyGpuStream(GpuStream stream);
struct GpuStreamDeleter {
  void operator()(GpuStream s) const { destroyGpuStream(s); }
};
using OwnedGpuStream = std::unique_ptr<CUstream_st, GpuStreamDeleter>;
// Enqueues a device-to-device copy on `stream`, then makes `after` wait for it (the next work of
// `after` may overwrite `src`). Throws in builds without CUDA.
void copyDeviceAsync(void* dst, const void* src, size_t bytes, GpuStream stream, GpuStream after);

// An image's way from the device to the host that does not hold up the next frame: a device
// buffer (to render into), page-locked host memory, and an event; start() enqueues the copy on a
// stream, wait() blocks until it has arrived. Throws in builds without CUDA.
class PinnedDownload {
 public:
  explicit PinnedDownload(size_t bytes);
  PinnedDownload(const PinnedDownload&) = delete;
  PinnedDownload& operator=(const PinnedDownload&) = delete;
  ~PinnedDownload();
  size_t bytes() const { return bytes_; }
  void* device() const { return device_; }
  void start(GpuStream stream);
  const void* wait();

 private:
  size_t bytes_;
  void* device_ = nullptr;
  void* host_ = nullptr;
  void* event_ = nullptr;  // cudaEvent_t
};

}  // namespace gvdp::detail
