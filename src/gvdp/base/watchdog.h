// A watchdog over the host's waits on the GPU (GVDP_WATCHDOG_S in the environment: seconds; unset
// or 0: off). A wait that has not ended after that long ends the process with status 3 and one
// line naming what the host waited for and the phases it was in, outermost first (the NVTX ranges
// of base/cuda_util.h), e.g. "gvdp: the GPU did not finish in 30 s: a copy to the host, in dp
// frame > dp sweep > render pass". Without it a kernel that never ends hangs the program without
// a word of where (dp's rare hang: docs/DESIGN.md).
#pragma once

namespace gvdp::detail {

// While it lives, the calling thread is in phase `name` (a string that outlives it, such as a
// literal); phases nest.
class WatchPhase {
 public:
  explicit WatchPhase(const char* name);
  ~WatchPhase();
  WatchPhase(const WatchPhase&) = delete;
  WatchPhase& operator=(const WatchPhase&) = delete;
};

// While it lives, the calling thread waits on the GPU for `what` (a string that outlives it);
// past the watchdog's limit the process ends. The first one starts the watchdog from
// GVDP_WATCHDOG_S (a bad value is an input error).
class WatchedWait {
 public:
  explicit WatchedWait(const char* what);
  ~WatchedWait();
  WatchedWait(const WatchedWait&) = delete;
  WatchedWait& operator=(const WatchedWait&) = delete;
};

// Starts the watchdog with a limit of `seconds` (> 0): once per process, later calls change
// nothing.
void startWatchdog(double seconds);

}  // namespace gvdp::detail
