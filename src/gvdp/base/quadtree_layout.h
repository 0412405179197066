// The layout of a quadtree's per-node values (a mipmap stored root first): depth d is a
// 2^d x 2^d square at offset (4^d - 1) / 3, so one formula addresses every level on either
// backend. Shared by the importance pre-pass (sched/importance.h), which fills it, and the tile
// subdivision (tiles/quadtree.h), which reads it.
#pragma once

#include <cstdint>

#include "gvdp/base/defs.h"

namespace gvdp::detail {

GVDP_HD inline uint64_t mipmapDepthOffset(int depth) {
  return ((uint64_t{1} << (2 * depth)) - 1) / 3;
}
// Values of a quadtree of `levels` levels below its root.
GVDP_HD inline uint64_t mipmapSize(int levels) {
  return mipmapDepthOffset(levels + 1);
}
GVDP_HD inline uint64_t mipmapIndex(int depth, int x, int y) {
  return mipmapDepthOffset(depth) + (uint64_t{static_cast<uint32_t>(y)} << depth) +
         static_cast<uint32_t>(x);
}

}  // namespace gvdp::detail
