#include "gvdp/base/host_memory.h"

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

namespace gvdp::detail {
namespace {

// MemAvailable from /proc/meminfo (free memory plus what the kernel can reclaim without swapping).
std::optional<uint64_t> memAvailable() {
  std::ifstream in("/proc/meminfo");
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string key;
    uint64_t kib = 0;
    if (fields >> key >> kib && key == "MemAvailable:") return kib * 1024;
  }
  return std::nullopt;
}

// Pages not in use, where /proc/meminfo cannot be read.
std::optional<uint64_t> freePages() {
  long pages = sysconf(_SC_AVPHYS_PAGES), size = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || size <= 0) return std::nullopt;
  return static_cast<uint64_t>(pages) * static_cast<uint64_t>(size);
}

std::optional<uint64_t> readNumber(const char* path) {
  std::ifstream in(path);
  uint64_t n = 0;
  if (in >> n) return n;
  return std::nullopt;
}

// Room left under a cgroup v2 memory limit; nullopt without one ("max" or no such file).
std::optional<uint64_t> cgroupRoom() {
  std::optional<uint64_t> limit = readNumber("/sys/fs/cgroup/memory.max");
  if (!limit) return std::nullopt;
  uint64_t used = readNumber("/sys/fs/cgroup/memory.current").value_or(0);
  return *limit > used ? *limit - used : 0;
}

}  // namespace

std::optional<uint64_t> hostAvailableMemoryBytes() {
  std::optional<uint64_t> host = memAvailable();
  if (!host) host = freePages();
  std::optional<uint64_t> room = cgroupRoom();
  if (host && room) return std::min(*host, *room);
  return host ? host : room;
}

}  // namespace gvdp::detail
