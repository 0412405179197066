// The sp loop as one CUDA graph (graph_kernels.cu): a conditional WHILE node whose body is
// render pass -> swap the live-ray lists -> production -> clear the requests, with the loop's
// state in device memory, so a frame is one graph launch and one read-back.
#pragma once

#include <cuda_runtime_api.h>

#include "gvdp/cache/cache_view.h"
#include "gvdp/render/brick_pool.h"
#include "gvdp/render/frame.h"
#include "gvdp/render/march.h"

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

// Who repeats the loop's body. Device: the graph's conditional WHILE node (the scheduler).
// Host: the graph is the body alone, launched again while loop.stop is 0 (one read-back per
// pass, as sp): the same kernels and protocol, for the tools that cannot check the kernels of a
// conditional node's body (compute-sanitizer 2025.3's racecheck crashes in its own library on
// this graph, its synccheck reports barrier divergence in a trivially correct kernel there:
// scripts/probe/graph_probe.cu). GVDP_GRAPH_LOOP=host selects it (scripts/gpu_check.sh).
enum class GraphDriver { Device, Host };

// Builds and instantiates the graph for this device; its kernels read the uploaded frame and
// *loop.
cudaGraphExec_t buildSpGraph(GraphLoop* loop, GraphDriver driver);
void uploadGraphFrame(const GraphFrame& frame);

}  // namespace gvdp
