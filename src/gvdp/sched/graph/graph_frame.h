// What the graph's kernels share (graph_kernels.cu, graph_produce.cuh): the frame in device
// memory, the loop's state and how the loop ended.
#pragma once

#include "gvdp/cache/cache_view.h"
#include "gvdp/render/brick_pool.h"
#include "gvdp/render/frame.h"
#include "gvdp/render/march.h"

namespace gvdp::detail {

// What the graph's kernels read per frame: uploaded to device memory before each launch (a
// graph's kernel parameters are fixed when it is built).
struct GraphFrame {
  FrameSetup frame;
  CacheView cache;
  BrickPool pool;
  RayState* payload;
};

enum GraphExit : uint32_t {
  GRAPH_DONE = 0,        // every ray finished
  GRAPH_FAILED = 1,      // a production found no free slot: the host refills and goes on
  GRAPH_MAX_PASSES = 2,  // SP_MAX_PASSES reached: the host degrades the frame and goes on
};

// The loop state, in device memory; the host sets it before a launch and reads it after.
struct GraphLoop {
  uint32_t* live;  // rays of the next render pass (after the first, tiled one)
  uint32_t* next;  // rays stopped in the current pass
  uint32_t liveCount, nextCount, passes, stop, exit, failedBefore;
  uint32_t cursor;  // next item of the current pass (render: per warp; production: per block)
};

}  // namespace gvdp::detail
