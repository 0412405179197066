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

// Profiling hook (profile/ installs one): a worker ran tasks of `kind` from start to end (ns);
// `report` files it into `sink` (a timeline). Each thread has its own: a run carries its caller's
// to the workers, so two threads recording two timelines on the shared pool (two renderers) each
// get only their own runs' records, all pushed before their run returns.
struct TaskObserver {
  void (*report)(void* sink, uint8_t kind, int worker, uint64_t startNs, uint64_t endNs) = nullptr;
  void* sink = nullptr;
  explicit operator bool() const { return report != nullptr; }
  void operator()(uint8_t kind, int worker, uint64_t startNs, uint64_t endNs) const {
    report(sink, kind, worker, startNs, endNs);
  }
};
void setTaskObserver(TaskObserver observer);  // for the calling thread's runs; {}: off
TaskObserver taskObserver();                  // inside a run's body: the run's observer, if any

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

  // The task observer of the run in progress (inside a body); empty when it is not recorded.
  TaskObserver runObserver() const { return observer_; }

 private:
  void workerLoop(int worker);
  bool drain(int worker);  // whether it ran a chunk
  void drainRecorded(int worker);

  std::vector<std::thread> workers_;
  std::mutex callers_;  // held by the run in progress
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(int64_t, int64_t, int)>* body_ = nullptr;
  int64_t n_ = 0, chunk_ = 1;
  uint8_t kind_ = 0;
  TaskObserver observer_;  // the run's: its caller's, set with the run under mutex_
  std::atomic<int64_t> next_{0};
  int active_ = 0;
  uint64_t generation_ = 0;
  bool stop_ = false;
};

constexpr uint8_t NO_RECORD = 255;  // a run whose tasks report themselves

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
