// The clock around a frame's work: CUDA events on the GPU (the time of the work queued between
// start and stop), the wall clock on the CPU. Scheduler::render() runs it for every scheduler.
#pragma once

#include <chrono>
#include <memory>

#include "gvdp/base/gpu.h"

namespace gvdp::detail {

class FrameClock {
 public:
  virtual ~FrameClock() = default;
  virtual void start() = 0;
  virtual double stopMs() = 0;  // milliseconds since start()
};

class CpuFrameClock final : public FrameClock {
 public:
  void start() override { t0_ = std::chrono::steady_clock::now(); }
  double stopMs() override {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0_)
        .count();
  }

 private:
  std::chrono::steady_clock::time_point t0_;
};

// CUDA events on `stream` (CUDA builds only).
std::unique_ptr<FrameClock> makeGpuFrameClock(GpuStream stream);

}  // namespace gvdp::detail
