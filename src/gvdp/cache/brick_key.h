// Indirection-table entries and brick keys (paper 3.2). An entry is a uint32: a brick-pool slot,
// or one of three states above every slot. A BrickKey names a brick by level and global brick
// coordinates (the inverse table stores one per slot).
#pragma once

#include <cstdint>

#include "gvdp/base/vecmath.h"

namespace gvdp {

constexpr uint32_t ENTRY_MISSING = 0xffffffffu;
constexpr uint32_t ENTRY_IN_PRODUCTION = 0xfffffffeu;
constexpr uint32_t ENTRY_EMPTY = 0xfffffffdu;
constexpr uint32_t MAX_SLOTS = 0xfffffff0u;  // slots are below every special value

GVDP_HD GVDP_INLINE bool isSlot(uint32_t entry) {
  return entry < MAX_SLOTS;
}

struct BrickKey {
  Vec3i brick;  // global brick coordinates at `level`
  int level;    // -1: no brick (an unmapped slot in the inverse table)
};

constexpr int NO_LEVEL = -1;

}  // namespace gvdp
