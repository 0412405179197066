// What the host knows about the GPU without including CUDA headers: whether this build has the
// CUDA backend and whether a device is present at run time (GPU tests skip when not).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace gvdp::detail {

bool cudaBuilt();
bool cudaDeviceAvailable();
// One line per device (name, SMs, memory), or why there is none.
std::string cudaDeviceSummary();
// Free memory of the current device (cudaMemGetInfo); nullopt without a device.
std::optional<uint64_t> cudaFreeMemoryBytes();
// Enqueues a device-to-device copy on `stream` (a cudaStream_t); throws in builds without CUDA.
void copyDeviceAsync(void* dst, const void* src, size_t bytes, void* stream);

}  // namespace gvdp::detail
