// Indirection-table entries and brick keys (paper 3.2). An entry is a uint32: a brick-pool slot,
// or a state above every slot: MISSING, EMPTY (with the radius of the empty cube of bricks
// around it: emptyEntry), IN_PRODUCTION, or (pt) in production by the production task
// PRODUCTION_TASK + id, whose rays wait on that task's list. A BrickKey names a
// brick by level and global brick coordinates (the inverse table stores one per slot).
#pragma once

#include <cstdint>

#include "gvdp/base/vecmath.h"

namespace gvdp::detail {

constexpr uint32_t ENTRY_MISSING = 0xffffffffu;
constexpr uint32_t ENTRY_IN_PRODUCTION = 0xfffffffeu;
constexpr uint32_t ENTRY_EMPTY = 0xfffffffdu;
constexpr uint32_t MAX_SLOTS = 0x80000000u;  // slots are below every special value
constexpr uint32_t ENTRY_PRODUCTION_TASK = MAX_SLOTS;
constexpr uint32_t MAX_PRODUCTION_TASKS = 0x7ffffff0u;

// An EMPTY entry of code k (0..MAX_EMPTY_CODE) says more than "this brick is empty": every brick
// of its level within emptyRadius(k) = 2^k - 1 bricks of it (a cube of side 2^(k+1) - 1) is
// empty too, by the producer's box bound (cache/produce.h: emptyCubeCode), so a ray skips the
// whole cube with one lookup. Code 0 is the plain EMPTY brick.
constexpr int MAX_EMPTY_CODE = 12;
static_assert(ENTRY_EMPTY - MAX_EMPTY_CODE >= ENTRY_PRODUCTION_TASK + MAX_PRODUCTION_TASKS,
              "EMPTY codes overlap the production-task names");

GVDP_HD GVDP_INLINE uint32_t emptyEntry(int code) {
  return ENTRY_EMPTY - static_cast<uint32_t>(code);
}

GVDP_HD GVDP_INLINE bool isEmptyEntry(uint32_t entry) {
  return entry <= ENTRY_EMPTY && entry >= ENTRY_EMPTY - MAX_EMPTY_CODE;
}

GVDP_HD GVDP_INLINE int emptyRadius(uint32_t entry) {
  return (1 << (ENTRY_EMPTY - entry)) - 1;
}

GVDP_HD GVDP_INLINE bool isSlot(uint32_t entry) {
  return entry < MAX_SLOTS;
}

// The pt task id an entry names, or -1 (resident, EMPTY, MISSING or plain IN_PRODUCTION).
GVDP_HD GVDP_INLINE int64_t productionTaskOf(uint32_t entry) {
  return entry >= ENTRY_PRODUCTION_TASK && entry < ENTRY_PRODUCTION_TASK + MAX_PRODUCTION_TASKS
             ? static_cast<int64_t>(entry - ENTRY_PRODUCTION_TASK)
             : -1;
}

struct BrickKey {
  Vec3i brick;  // global brick coordinates at `level`
  int level;    // -1: no brick (an unmapped slot in the inverse table)
};

constexpr int NO_LEVEL = -1;

}  // namespace gvdp::detail
