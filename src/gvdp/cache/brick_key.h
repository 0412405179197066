// Indirection-table entries and brick keys (paper 3.2). An entry is a uint32: a brick-pool slot,
// or a state above every slot: MISSING, EMPTY (with the empty box of bricks around it:
// emptyEntry), CLEAR (with the box of bricks zero at its level: clearEntry), IN_PRODUCTION, or (pt)
// in production by the production task PRODUCTION_TASK + id, whose rays wait on that task's list. A
// BrickKey names a brick by level and global brick coordinates (the inverse table stores one per
// slot).
#pragma once

#include <cstdint>

#include "gvdp/base/vecmath.h"
#include "gvdp/render/empty_box.h"

namespace gvdp::detail {

constexpr uint32_t ENTRY_MISSING = 0xffffffffu;
constexpr uint32_t ENTRY_IN_PRODUCTION = 0xfffffffeu;
constexpr uint32_t MAX_SLOTS = 0x80000000u;  // slot entries are below every special value
// A slot entry published in the running frame carries ENTRY_FRESH: a reader that may run while
// bricks are published (PoolReads::Coherent, cached_access.h) acquires such an entry before it
// reads the brick, and reads every other brick without one (docs/DESIGN.md, "Memory model").
// The frame's end clears the mark (BrickCache::settleFresh), so pool slots stay below it.
constexpr uint32_t ENTRY_FRESH = 0x40000000u;
constexpr uint32_t SLOT_LIMIT = ENTRY_FRESH;  // pool slots are below it
constexpr uint32_t ENTRY_PRODUCTION_TASK = MAX_SLOTS;
constexpr uint32_t MAX_PRODUCTION_TASKS = 0x70000000u;

// An EMPTY entry says more than "this brick is empty": the box of bricks of its level that
// reaches below[a] bricks down and above[a] bricks up from it along each axis a is empty too, by
// the producer's box bound (cache/produce.h: growEmptyBoxes), then grown over the bricks the table
// knows empty in the next frame (cache/table_boxes.h), so a ray leaves the whole box with one
// lookup. The entry is ENTRY_EMPTY with the box's reach codes (render/empty_box.h) in its
// low 24 bits; ENTRY_EMPTY itself is the plain EMPTY brick.
constexpr uint32_t ENTRY_EMPTY = 0xf0000000u;
constexpr uint32_t EMPTY_CODES_MASK = 0xffffffu;
static_assert(ENTRY_EMPTY >= ENTRY_PRODUCTION_TASK + MAX_PRODUCTION_TASKS,
              "EMPTY entries overlap the production-task names");

// A CLEAR brick was produced and every one of its samples (the border's too) is zero, but the
// producer did not flag it empty: a finer level may hold something there (the empty flag's
// margin, world/producer.h). It samples zero at its own level, as a resident brick whose cells
// are all clear would, and holds no slot (cache/produce.h: commitBrick). Perlin's and fbm's
// walkthroughs leave two thirds of their resident bricks all zero, forest's and the spheres' a
// quarter (frame 12, CPU, 300x200 at --lod-width 1500). Like an EMPTY entry it names a box, in
// its low 24 bits, ENTRY_CLEAR alone the brick alone: the bricks of that box are zero at its
// level, as the table knew them when the box grew, in the next frame (cache/table_boxes.h:
// growTableBox), so a ray of that level leaves the box with one lookup; a finer
// level may hold matter in it.
constexpr uint32_t ENTRY_CLEAR = 0xf1000000u;
static_assert((ENTRY_EMPTY | EMPTY_CODES_MASK) < ENTRY_CLEAR, "CLEAR entries overlap EMPTY ones");
static_assert((ENTRY_CLEAR | EMPTY_CODES_MASK) < ENTRY_IN_PRODUCTION,
              "CLEAR entries overlap the states");

GVDP_HD GVDP_INLINE uint32_t emptyEntry(const EmptyReachCodes& c) {
  return ENTRY_EMPTY | c.packed();
}

GVDP_HD GVDP_INLINE bool isEmptyEntry(uint32_t entry) {
  return (entry & ~EMPTY_CODES_MASK) == ENTRY_EMPTY;
}

GVDP_HD GVDP_INLINE uint32_t clearEntry(const EmptyReachCodes& c) {
  return ENTRY_CLEAR | c.packed();
}

GVDP_HD GVDP_INLINE bool isClearEntry(uint32_t entry) {
  return (entry & ~EMPTY_CODES_MASK) == ENTRY_CLEAR;
}

// The box an EMPTY (or CLEAR) entry names, in bricks from its own: [brick - below, brick + above].
struct EmptyReach {
  Vec3i below, above;
};

GVDP_HD GVDP_INLINE EmptyReach emptyReach(uint32_t entry) {
  auto r = [&](int face) { return emptyReachThrough(entry, face); };
  return {{r(0), r(1), r(2)}, {r(3), r(4), r(5)}};
}

// The largest box the codes can name inside `box` (emptyReach's inverse, each reach rounded down).
GVDP_HD GVDP_INLINE EmptyReachCodes codesWithin(const EmptyReach& box) {
  auto c = [](int reach) { return emptyReachCodeAtMost(reach); };
  return {{c(box.below.x), c(box.below.y), c(box.below.z), c(box.above.x), c(box.above.y),
           c(box.above.z)}};
}

GVDP_HD GVDP_INLINE bool isSlot(uint32_t entry) {
  return entry < MAX_SLOTS;
}

// The slot a slot entry (isSlot) holds, and whether it was published in the running frame.
GVDP_HD GVDP_INLINE uint32_t slotOf(uint32_t entry) {
  return entry & ~ENTRY_FRESH;
}
GVDP_HD GVDP_INLINE bool isFresh(uint32_t entry) {
  return (entry & ENTRY_FRESH) != 0u;
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
