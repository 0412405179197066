// Float operations rounded one at a time on both backends: __fmul_rn, __fadd_rn, __fsub_rn and
// __fdiv_rn on the GPU (nvcc would otherwise contract a * b + c into one FMA, one rounding
// instead of two), the plain operators on the host (sources that need the same bits are built
// with -ffp-contract=off). For results both backends must agree on bit for bit: the scenes'
// sin-hash (world/hash.h), the kd-tree's rules (mesh/box.h).
#pragma once

#include "gvdp/base/defs.h"

namespace gvdp::detail {

GVDP_HD GVDP_INLINE float roundedMul(float a, float b) {
#if GVDP_IS_GPU_CODE
  return __fmul_rn(a, b);
#else
  return a * b;
#endif
}
GVDP_HD GVDP_INLINE float roundedAdd(float a, float b) {
#if GVDP_IS_GPU_CODE
  return __fadd_rn(a, b);
#else
  return a + b;
#endif
}
GVDP_HD GVDP_INLINE float roundedSub(float a, float b) {
#if GVDP_IS_GPU_CODE
  return __fsub_rn(a, b);
#else
  return a - b;
#endif
}
GVDP_HD GVDP_INLINE float roundedDiv(float a, float b) {
#if GVDP_IS_GPU_CODE
  return __fdiv_rn(a, b);
#else
  return a / b;
#endif
}

}  // namespace gvdp::detail
