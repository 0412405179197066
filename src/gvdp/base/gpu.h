// What the host knows about the GPU without including CUDA headers: whether this build has the
// CUDA backend and whether a device is present at run time (GPU tests skip when not).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace gvdp {

bool cudaBuilt();
bool cudaDeviceAvailable();
// One line per device (name, SMs, memory), or why there is none.
std::string cudaDeviceSummary();
// Free memory of the current device (cudaMemGetInfo); nullopt without a device.
std::optional<uint64_t> cudaFreeMemoryBytes();

}  // namespace gvdp
