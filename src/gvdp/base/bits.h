// Bit scans for host and device code.
#pragma once

#include <bit>
#include <cstdint>

#include "gvdp/base/defs.h"

namespace gvdp::detail {

// The index of the lowest set bit of m (m != 0).
GVDP_HD GVDP_INLINE int lowestBit(uint32_t m) {
#if GVDP_IS_GPU_CODE
  return __ffs(static_cast<int>(m)) - 1;
#else
  return std::countr_zero(m);
#endif
}

}  // namespace gvdp::detail
