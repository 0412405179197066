// Indirection-table entries and brick keys (paper 3.2). An entry is a uint32: a brick-pool slot,
// or a state above every slot: MISSING, EMPTY, IN_PRODUCTION, or (pt) in production by the
// production task PRODUCTION_TASK + id, whose rays wait on that task's list. A BrickKey names a
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
