// The CPU backend's stand-in for device-side launches: a queue of tasks that worker threads pull
// until it is empty and no task is running (a "launch" pushes a task). A capacity plays the part
// of CDP's pending-launch buffer: a push beyond it fails, as a device launch would.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>

namespace gvdp::detail {

template <class Task>
class TaskQueue {
 public:
  explicit TaskQueue(size_t capacity) : capacity_(capacity) {}

  bool push(const Task& t) {
    {
      std::lock_guard lock(mutex_);
      if (tasks_.size() >= capacity_) return false;
      tasks_.push_back(t);
    }
    ready_.notify_one();
    return true;
  }
  // Takes a task, waiting while others may still push; false once everything is done.
  bool pop(Task& t) {
    std::unique_lock lock(mutex_);
    ready_.wait(lock, [&] { return !tasks_.empty() || running_ == 0; });
    if (tasks_.empty()) return false;
    t = tasks_.front();
    tasks_.pop_front();
    ++running_;
    return true;
  }
  void finished() {
    std::lock_guard lock(mutex_);
    if (--running_ == 0 && tasks_.empty()) ready_.notify_all();
  }

 private:
  size_t capacity_;
  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<Task> tasks_;
  size_t running_ = 0;
};

}  // namespace gvdp::detail
