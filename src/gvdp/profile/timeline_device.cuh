// Block-level instrumentation of CUDA kernels: put `BlockTimer timer(timeline, TaskKind::X);` first
// in a kernel, with the frame's TimelineView (a kernel parameter: no device global, so kernels
// instantiated in a user's translation unit record too). Every thread takes part (start = atomicMin
// of %globaltimer over the block's threads, end = atomicMax); the last thread to leave writes the
// record, so kernels may return early. Free when profiling is off: one load and a uniform branch
// per thread.
#pragma once

#include "gvdp/base/clock.h"
#include "gvdp/profile/timeline.h"

namespace gvdp::detail {

__device__ inline uint32_t smId() {
  uint32_t id;
  asm volatile("mov.u32 %0, %%smid;" : "=r"(id));
  return id;
}

class BlockTimer {
 public:
  __device__ BlockTimer(const TimelineView& timeline, TaskKind kind)
      : timeline_(timeline), on_(timeline.enabled()), kind_(kind) {
    if (!on_) return;
    __shared__ Span span;
    span_ = &span;
    if (threadIdx.x + threadIdx.y + threadIdx.z == 0) {
      span.start = ~0ull;
      span.end = 0;
      span.left = 0;
      span.sm = smId();
    }
    __syncthreads();
    atomicMin(&span.start, static_cast<unsigned long long>(clockNanoseconds()));
  }
  __device__ ~BlockTimer() {
    if (!on_) return;
    atomicMax(&span_->end, static_cast<unsigned long long>(clockNanoseconds()));
    __threadfence_block();
    unsigned threads = blockDim.x * blockDim.y * blockDim.z;
    if (atomicAdd(&span_->left, 1u) + 1 == threads) {
      __threadfence_block();
      timeline_.push({span_->start, span_->end, static_cast<uint16_t>(span_->sm),
                      static_cast<uint16_t>(smId()), kind_});
    }
  }

 private:
  struct Span {
    unsigned long long start, end;
    unsigned left, sm;
  };
  TimelineView timeline_;
  bool on_;
  TaskKind kind_;
  Span* span_ = nullptr;
};

}  // namespace gvdp::detail
