// Atomics for the one-source bodies: CUDA atomics on the GPU, std::atomic_ref on the CPU (so the
// CPU backend runs the same protocol under ThreadSanitizer). Loads acquire and stores release,
// which is what publishing a brick (write samples, fence, then entry) needs; on the CPU they are
// sequentially consistent, which also orders dp's store-then-load (fenceSeqCst is then a no-op:
// ThreadSanitizer does not model standalone fences).
#pragma once

#include <cstdint>

#include "gvdp/base/defs.h"

#if !GVDP_IS_GPU_CODE
#include <atomic>
#include <thread>
#endif

namespace gvdp::detail {

GVDP_HD GVDP_INLINE uint32_t atomicCas32(uint32_t* p, uint32_t expected, uint32_t desired) {
#if GVDP_IS_GPU_CODE
  return atomicCAS(p, expected, desired);
#else
  std::atomic_ref<uint32_t>(*p).compare_exchange_strong(expected, desired,
                                                        std::memory_order_seq_cst);
  return expected;  // the value found: equal to the argument on success
#endif
}

GVDP_HD GVDP_INLINE uint64_t atomicCas64(uint64_t* p, uint64_t expected, uint64_t desired) {
#if GVDP_IS_GPU_CODE
  return atomicCAS(reinterpret_cast<unsigned long long*>(p),
                   static_cast<unsigned long long>(expected),
                   static_cast<unsigned long long>(desired));
#else
  std::atomic_ref<uint64_t>(*p).compare_exchange_strong(expected, desired,
                                                        std::memory_order_relaxed);
  return expected;
#endif
}

GVDP_HD GVDP_INLINE uint32_t atomicAdd32(uint32_t* p, uint32_t v) {
#if GVDP_IS_GPU_CODE
  return atomicAdd(p, v);
#else
  return std::atomic_ref<uint32_t>(*p).fetch_add(v, std::memory_order_relaxed);
#endif
}

GVDP_HD GVDP_INLINE uint32_t atomicMax32(uint32_t* p, uint32_t v) {
#if GVDP_IS_GPU_CODE
  return atomicMax(p, v);
#else
  std::atomic_ref<uint32_t> a(*p);
  uint32_t old = a.load(std::memory_order_relaxed);
  while (old < v && !a.compare_exchange_weak(old, v, std::memory_order_relaxed)) {
  }
  return old;
#endif
}

GVDP_HD GVDP_INLINE void atomicAdd64(uint64_t* p, uint64_t v) {
#if GVDP_IS_GPU_CODE
  atomicAdd(reinterpret_cast<unsigned long long*>(p), static_cast<unsigned long long>(v));
#else
  std::atomic_ref<uint64_t>(*p).fetch_add(v, std::memory_order_relaxed);
#endif
}

GVDP_HD GVDP_INLINE uint32_t atomicExch32(uint32_t* p, uint32_t v) {
#if GVDP_IS_GPU_CODE
  return atomicExch(p, v);
#else
  return std::atomic_ref<uint32_t>(*p).exchange(v, std::memory_order_seq_cst);
#endif
}

// On the GPU one ld.acquire.gpu: the loads after it see what the writer stored before its
// release (storeRelease32: fence, then the store); no fence of the reader's own (a volatile load
// and __threadfence() cost every brick lookup a full fence, 10-13% of the render floor).
GVDP_HD GVDP_INLINE uint32_t loadAcquire32(const uint32_t* p) {
#if GVDP_IS_GPU_CODE
  uint32_t v;
  asm volatile("ld.acquire.gpu.u32 %0, [%1];" : "=r"(v) : "l"(p) : "memory");
  return v;
#else
  return std::atomic_ref<uint32_t>(*const_cast<uint32_t*>(p)).load(std::memory_order_seq_cst);
#endif
}

GVDP_HD GVDP_INLINE uint64_t loadAcquire64(const uint64_t* p) {
#if GVDP_IS_GPU_CODE
  uint64_t v;
  asm volatile("ld.acquire.gpu.u64 %0, [%1];" : "=l"(v) : "l"(p) : "memory");
  return v;
#else
  return std::atomic_ref<uint64_t>(*const_cast<uint64_t*>(p)).load(std::memory_order_seq_cst);
#endif
}

GVDP_HD GVDP_INLINE void storeRelease64(uint64_t* p, uint64_t v) {
#if GVDP_IS_GPU_CODE
  __threadfence();
  *reinterpret_cast<volatile uint64_t*>(p) = v;
#else
  std::atomic_ref<uint64_t>(*p).store(v, std::memory_order_seq_cst);
#endif
}

// Loads a word another thread may write concurrently, without ordering anything else.
GVDP_HD GVDP_INLINE uint32_t loadRelaxed32(const uint32_t* p) {
#if GVDP_IS_GPU_CODE
  return *reinterpret_cast<const volatile uint32_t*>(p);
#else
  return std::atomic_ref<uint32_t>(*const_cast<uint32_t*>(p)).load(std::memory_order_relaxed);
#endif
}

GVDP_HD GVDP_INLINE void storeRelease32(uint32_t* p, uint32_t v) {
#if GVDP_IS_GPU_CODE
  __threadfence();
  *reinterpret_cast<volatile uint32_t*>(p) = v;
#else
  std::atomic_ref<uint32_t>(*p).store(v, std::memory_order_seq_cst);
#endif
}

GVDP_HD GVDP_INLINE void storeRelaxed32(uint32_t* p, uint32_t v) {
#if GVDP_IS_GPU_CODE
  *reinterpret_cast<volatile uint32_t*>(p) = v;
#else
  std::atomic_ref<uint32_t>(*p).store(v, std::memory_order_relaxed);
#endif
}

// Backs off inside a spin-wait (the awaited store comes from another warp or thread).
GVDP_HD GVDP_INLINE void spinPause() {
#if GVDP_IS_GPU_CODE
  __nanosleep(32);
#else
  std::this_thread::yield();
#endif
}

// Orders a store before a later load (the Dekker pattern of dp's race-free relaunch).
GVDP_HD GVDP_INLINE void fenceSeqCst() {
#if GVDP_IS_GPU_CODE
  __threadfence();
#endif
}

}  // namespace gvdp::detail
