// CPU backend of ParallelFor (pbrt-v4 style): a fixed pool of worker threads that runs
// fn(i) for i in [0, n) in chunks pulled from an atomic counter. The caller thread works too,
// so a pool of one thread runs everything inline.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace gvdp::detail {

class ThreadPool {
 public:
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return static_cast<int>(workers_.size()) + 1; }

  // Runs body(begin, end, worker) over [0, n) in chunks of `chunk`; returns when all are done.
  // Calls from several threads take turns (body must not call run()).
  // worker is in [0, size()): 0 is the calling thread. `kind` labels the work in the timeline
  // (profile/): while the calling thread records one, every worker leaves one record per run.
  void run(int64_t n, int64_t chunk, const std::function<void(int64_t, int64_t, int)>& body,
           uint8_t kind = 0);

  // The process-wide pool, sized from GVDP_THREADS or the hardware concurrency.
  static ThreadPool& global();

  // The task observer of the run in progress (inside a body), nullptr when it is not recorded.
  auto runObserver() const { return observer_.load(); }

 private:
  void workerLoop(int worker);
  void drain(int worker);
  void drainRecorded(int worker);

  std::vector<std::thread> workers_;
  std::mutex callers_;  // held by the run in progress
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(int64_t, int64_t, int)>* body_ = nullptr;
  int64_t n_ = 0, chunk_ = 1;
  uint8_t kind_ = 0;
  std::atomic<void (*)(uint8_t, int, uint64_t, uint64_t)> observer_{nullptr};  // the run's
  std::atomic<int64_t> next_{0};
  int active_ = 0;
  uint64_t generation_ = 0;
  bool stop_ = false;
};

// Profiling hook (profile/ installs one): a worker ran tasks of `kind` from start to end (ns).
// It observes the runs of the thread that installed it only: another thread's runs on the shared
// pool (two renderers on two threads) are not recorded into its timeline, and cannot push into it
// after that thread's run has returned.
using TaskObserver = void (*)(uint8_t kind, int worker, uint64_t startNs, uint64_t endNs);
void setTaskObserver(TaskObserver observer);  // for the calling thread's runs; nullptr: off
TaskObserver taskObserver();                  // inside a run's body: the run's observer, if any
constexpr uint8_t NO_RECORD = 255;            // a run whose tasks report themselves

// fn(i) for every i in [0, n) on the global pool; `kind` is a TaskKind (profile/timeline.h).
template <class F>
void parallelFor(int64_t n, F&& fn, int64_t chunk = 64, uint8_t kind = 0) {
  ThreadPool::global().run(
      n, chunk,
      [&](int64_t b, int64_t e, int) {
        for (int64_t i = b; i < e; ++i) fn(i);
      },
      kind);
}

}  // namespace gvdp::detail
