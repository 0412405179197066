// The empty box of an EMPTY brick, as the march leaves it (render/march.h) and production grows
// it (cache/produce.h: growEmptyBoxes): from the brick, a reach in bricks of its level through
// each of the six faces, each a 4-bit code in 24 bits (face f at bit 4 f: below x, y, z, then
// above x, y, z). The codes 0, 1, 2, 3, 4, 6, 8, 12, ... 192 bricks have one mantissa bit, so a
// reach is at most 1.5x short of what the producer's bound allows.
#pragma once

#include <cstdint>

#include "gvdp/base/defs.h"

namespace gvdp::detail {

constexpr int MAX_EMPTY_REACH_CODE = 15;
constexpr int FACE_ABOVE = 3;  // face a + FACE_ABOVE is axis a's upper face

// The reach in bricks of a code: c below 4, else (2 or 3) * 2^(c/2 - 1).
GVDP_HD GVDP_INLINE int emptyReachOfCode(int code) {
  return code < 4 ? code : (2 | (code & 1)) << ((code >> 1) - 1);
}

// The largest code whose reach is at most r bricks (emptyReachOfCode's inverse, rounded down).
GVDP_HD GVDP_INLINE int emptyReachCodeAtMost(int r) {
  int c = MAX_EMPTY_REACH_CODE;
  while (c > 0 && emptyReachOfCode(c) > r) --c;
  return c;
}

// The reach through face f of the box named by `codes`.
GVDP_HD GVDP_INLINE int emptyReachThrough(uint32_t codes, int face) {
  return emptyReachOfCode(static_cast<int>(codes >> (4 * face)) & MAX_EMPTY_REACH_CODE);
}

// The six codes, one per face.
struct EmptyReachCodes {
  int face[6];

  GVDP_HD uint32_t packed() const {
    uint32_t c = 0;
    for (int f = 0; f < 6; ++f) c |= static_cast<uint32_t>(face[f]) << (4 * f);
    return c;
  }
  GVDP_HD static EmptyReachCodes unpacked(uint32_t codes) {
    EmptyReachCodes c{};
    for (int f = 0; f < 6; ++f)
      c.face[f] = static_cast<int>(codes >> (4 * f)) & MAX_EMPTY_REACH_CODE;
    return c;
  }
};

}  // namespace gvdp::detail
