// pt's work queues: a bounded lock-free ring of uint32 values (D. Vyukov's), one atomic per batch
// of items; its capacity for n items.
#pragma once

#include <cstdint>

#include "gvdp/base/atomics.h"
#include "gvdp/base/defs.h"

namespace gvdp::detail {

// A bounded multi-producer multi-consumer ring (D. Vyukov's): a slot is (sequence, value) in one
// 64-bit word; the producer of position p waits for sequence p and leaves p + 1, the consumer
// waits for p + 1 and leaves p + capacity, so each slot serves its laps strictly in order.
// Positions only grow within a frame (32 bits, wrapping harmlessly: capacity divides 2^32).
// Claims take items off `ready` with a single CAS and no retry loop: thousands of warps polling
// a queue with CAS loops on its head spent their time retrying (perlin frame: 133 ms, against
// 39 ms with one attempt per poll, H100).
struct Ring {
  uint64_t* slots;
  uint32_t mask;    // capacity - 1, capacity a power of two
  uint32_t* head;   // next position to claim
  uint32_t* tail;   // next position to reserve
  uint32_t* ready;  // items published and not claimed
};

GVDP_HD GVDP_INLINE uint64_t ringSlot(uint32_t sequence, uint32_t value) {
  return static_cast<uint64_t>(sequence) << 32 | value;
}

// Slot i of a ring whose first `filled` positions hold the values 0, 1, ... (free ids).
GVDP_HD GVDP_INLINE uint64_t ringInitialSlot(uint32_t i, uint32_t filled) {
  return i < filled ? ringSlot(i + 1, i) : ringSlot(i, 0);
}

GVDP_HD GVDP_INLINE uint32_t ringReserve(const Ring& r, uint32_t n) {
  return atomicAdd32(r.tail, n);
}

GVDP_HD GVDP_INLINE void ringStore(const Ring& r, uint32_t position, uint32_t value) {
  uint64_t* s = &r.slots[position & r.mask];
  while (static_cast<uint32_t>(loadAcquire64(s) >> 32) != position) spinPause();  // last lap
  storeRelease64(s, ringSlot(position + 1, value));
}

// Makes n stored items claimable.
GVDP_HD GVDP_INLINE void ringPublish(const Ring& r, uint32_t n) {
  atomicAdd32(r.ready, n);
}

GVDP_HD GVDP_INLINE void ringPush(const Ring& r, uint32_t value) {
  ringStore(r, ringReserve(r, 1), value);
  ringPublish(r, 1);
}

// Claims up to n published items: returns how many, the first position in *position. One CAS
// attempt, no retry loop: a worker that loses the race looks for other work and comes back.
GVDP_HD GVDP_INLINE uint32_t ringClaim(const Ring& r, uint32_t n, uint32_t* position) {
  uint32_t ready = loadRelaxed32(r.ready);
  if (ready == 0) return 0;
  uint32_t k = ready < n ? ready : n;
  if (atomicCas32(r.ready, ready, ready - k) != ready) return 0;
  *position = atomicAdd32(r.head, k);
  return k;
}

// The value at a claimed position (waiting for its producer's store); frees the slot.
GVDP_HD GVDP_INLINE uint32_t ringTake(const Ring& r, uint32_t position) {
  uint64_t* s = &r.slots[position & r.mask];
  uint64_t v;
  while (static_cast<uint32_t>((v = loadAcquire64(s)) >> 32) != position + 1) spinPause();
  storeRelease64(s, ringSlot(position + r.mask + 1, 0));
  return static_cast<uint32_t>(v);
}

// A ring capacity for at most n items at once: a power of two > n.
GVDP_HD GVDP_INLINE uint32_t ringCapacity(uint32_t n) {
  uint32_t c = 1;
  while (c <= n) c <<= 1;
  return c;
}

}  // namespace gvdp::detail
