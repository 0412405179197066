// The sp loop as one CUDA graph (graph_kernels.cu): a conditional WHILE node whose body is
// render pass -> swap the live-ray lists -> production -> clear the requests, with the loop's
// state in device memory, so a frame is one graph launch and one read-back.
#pragma once

#include <cuda_runtime_api.h>

#include "gvdp/cache/cache_view.h"
#include "gvdp/render/brick_pool.h"
#include "gvdp/render/frame.h"
#include "gvdp/render/march.h"
#include "gvdp/sched/graph/graph.h"

namespace gvdp {

// What the graph's kernels read per frame (uploadGraphFrame before each launch).
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

// Builds and instantiates the graph for this device; its kernels read the uploaded frame and
// *loop.
cudaGraphExec_t buildSpGraph(GraphLoop* loop, GraphDriver driver);
void uploadGraphFrame(const GraphFrame& frame);

}  // namespace gvdp
