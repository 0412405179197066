#include "gvdp/base/parallel.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <string>

#include "gvdp/base/clock.h"

namespace gvdp::detail {

ThreadPool::ThreadPool(int threads) {
  for (int w = 1; w < std::max(threads, 1); ++w)
    workers_.emplace_back([this, w] { workerLoop(w); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (auto& t : workers_) t.join();
}

bool ThreadPool::drain(int worker) {
  for (bool ran = false;; ran = true) {
    int64_t b = next_.fetch_add(chunk_);
    if (b >= n_) return ran;
    (*body_)(b, std::min(n_, b + chunk_), worker);
  }
}

namespace {
thread_local TaskObserver callerObserver;
}  // namespace

void setTaskObserver(TaskObserver o) {
  callerObserver = o;
}
TaskObserver taskObserver() {
  return ThreadPool::global().runObserver();
}

// With an observer, a worker's share of a run (if it got any chunk) is reported as one task.
void ThreadPool::drainRecorded(int worker) {
  TaskObserver o = observer_;
  if (!o || kind_ == NO_RECORD) {
    drain(worker);
    return;
  }
  // A worker that woke after its run returned finds no chunk (next_ still grows) and must not
  // report: the run's timeline may be gone.
  uint64_t start = clockNanoseconds();
  if (drain(worker)) o(kind_, worker, start, clockNanoseconds());
}

void ThreadPool::workerLoop(int worker) {
  uint64_t seen = 0;
  for (;;) {
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      ++active_;
    }
    drainRecorded(worker);
    {
      std::lock_guard lock(mutex_);
      if (--active_ == 0) done_.notify_all();
    }
  }
}

void ThreadPool::run(int64_t n, int64_t chunk,
                     const std::function<void(int64_t, int64_t, int)>& body, uint8_t kind) {
  if (n <= 0) return;
  // Runs from several threads (two renderers, each on a thread of its own) take turns.
  std::lock_guard turn(callers_);
  {
    // A worker that woke late for the previous run may still be inside drain() (finding no
    // work): the shared state must not change under it, or it would pair the old chunk size
    // with the new counter and run chunks twice or skip them.
    std::unique_lock lock(mutex_);
    done_.wait(lock, [&] { return active_ == 0; });
    body_ = &body;
    n_ = n;
    chunk_ = std::max<int64_t>(chunk, 1);
    kind_ = kind;
    observer_ = callerObserver;
    next_ = 0;
    ++generation_;
  }
  wake_.notify_all();
  drainRecorded(0);
  std::unique_lock lock(mutex_);
  // Workers that woke late find no chunk left and leave at once; wait for those still busy.
  done_.wait(lock, [&] { return active_ == 0; });
  body_ = nullptr;
}

ThreadPool& ThreadPool::global() {
  static ThreadPool pool([] {
    if (const char* env = std::getenv("GVDP_THREADS")) return std::max(1, std::atoi(env));
    return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  }());
  return pool;
}

}  // namespace gvdp::detail
