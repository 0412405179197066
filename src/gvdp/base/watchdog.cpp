#include "gvdp/base/watchdog.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "gvdp/base/error.h"

namespace gvdp::detail {
namespace {

constexpr int MAX_PHASES = 32;  // deeper phases are kept in the count, not named

// One thread's phases and wait, written by the thread, read by the watchdog.
struct ThreadWatch {
  std::atomic<int> depth{0};
  std::atomic<const char*> phases[MAX_PHASES] = {};
  std::atomic<const char*> waitingFor{nullptr};
  std::atomic<int64_t> since{0};  // steady clock, ns
};

std::mutex registryMutex;
std::vector<ThreadWatch*>& registry() {
  static std::vector<ThreadWatch*> threads;
  return threads;
}

struct Registration {
  ThreadWatch watch;
  Registration() {
    std::lock_guard<std::mutex> lock(registryMutex);
    registry().push_back(&watch);
  }
  ~Registration() {
    std::lock_guard<std::mutex> lock(registryMutex);
    auto& r = registry();
    r.erase(std::remove(r.begin(), r.end(), &watch), r.end());
  }
};

ThreadWatch& mine() {
  thread_local Registration registration;
  return registration.watch;
}

int64_t nowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

std::string overdueLine(const ThreadWatch& w, const char* what, double limit) {
  char head[64];
  std::snprintf(head, sizeof head, "gvdp: the GPU did not finish in %g s: ", limit);
  std::string line = head;
  line += what;
  int depth = std::min(w.depth.load(), MAX_PHASES);
  for (int i = 0; i < depth; ++i) {
    const char* phase = w.phases[i].load();
    line += i == 0 ? ", in " : " > ";
    line += phase ? phase : "?";
  }
  return line + "\n";
}

void watch(double limit) {
  const auto nap = std::chrono::duration<double>(std::min(1.0, limit / 4.0));
  for (;;) {
    std::this_thread::sleep_for(nap);
    std::lock_guard<std::mutex> lock(registryMutex);
    for (const ThreadWatch* w : registry()) {
      const char* what = w->waitingFor.load();
      if (what && static_cast<double>(nowNs() - w->since.load()) * 1e-9 > limit) {
        std::string line = overdueLine(*w, what, limit);
        std::fputs(line.c_str(), stderr);
        std::fflush(stderr);
        std::_Exit(3);  // no destructor: they would wait on the GPU again
      }
    }
  }
}

double limitFromEnvironment() {
  const char* v = std::getenv("GVDP_WATCHDOG_S");
  if (v == nullptr || *v == '\0') return 0.0;
  char* end = nullptr;
  double s = std::strtod(v, &end);
  GVDP_INPUT_CHECK(end != v && *end == '\0' && s >= 0.0 && s < 1e9, "bad GVDP_WATCHDOG_S '", v,
                   "' (expected seconds, 0: off)");
  return s;
}

}  // namespace

WatchPhase::WatchPhase(const char* name) {
  ThreadWatch& w = mine();
  int d = w.depth.load(std::memory_order_relaxed);
  if (d < MAX_PHASES) w.phases[d].store(name);
  w.depth.store(d + 1);
}

WatchPhase::~WatchPhase() {
  ThreadWatch& w = mine();
  w.depth.store(w.depth.load(std::memory_order_relaxed) - 1);
}

WatchedWait::WatchedWait(const char* what) {
  static const double limit = limitFromEnvironment();
  if (limit > 0.0) startWatchdog(limit);
  ThreadWatch& w = mine();
  w.since.store(nowNs());
  w.waitingFor.store(what);
}

WatchedWait::~WatchedWait() {
  mine().waitingFor.store(nullptr);
}

void startWatchdog(double seconds) {
  static std::once_flag once;
  std::call_once(once, [seconds] { std::thread(watch, seconds).detach(); });
}

}  // namespace gvdp::detail
