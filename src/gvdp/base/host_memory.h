// What the host can give the CPU backend: the memory available now (Linux's MemAvailable, capped
// by a cgroup v2 limit when the process runs under one). Sizes are checked against it before the
// structures are allocated, so that a pool too large for the machine is refused in one line.
#pragma once

#include <cstdint>
#include <optional>

namespace gvdp::detail {

// Bytes the host can still give this process; nullopt when it cannot be told.
std::optional<uint64_t> hostAvailableMemoryBytes();

}  // namespace gvdp::detail
