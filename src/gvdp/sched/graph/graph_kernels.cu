// Kernels of the graph scheduler: the render pass as a resident grid whose warps claim their next
// items from a cursor, over counts in device memory (a graph's launch sizes are fixed), and the
// two one-thread control kernels that swap the live-ray lists and set the WHILE node's condition
// (cudaGraphSetConditional). The production node depends on the producer: graph_produce.cuh.
#include "gvdp/base/cuda_util.h"
#include "gvdp/profile/timeline_device.cuh"
#include "gvdp/sched/block_copy.cuh"
#include "gvdp/sched/compaction.cuh"
#include "gvdp/sched/graph/graph_cuda.h"
#include "gvdp/sched/producer_kernels_cuda.h"
#include "gvdp/sched/ray_tasks_warp.cuh"
#include "gvdp/sched/sp/sp.h"

namespace gvdp::detail {
namespace {

// Pass 0 covers the screen in 8x8 tiles from fresh states; later passes the live list.
__global__ void __launch_bounds__(RENDER_BLOCK, RENDER_BLOCKS_PER_SM)
    graphRenderKernel(const GraphFrame* __restrict__ frame, GraphLoop* loop) {
  __shared__ WarpMarchShared shared[RENDER_BLOCK_WARPS];
  const GraphFrame& graphFrame = blockCopy(frame);
  BlockTimer timer(graphFrame.frame.timeline, TaskKind::Render);
  const FrameSetup& f = graphFrame.frame;
  bool tiled = loop->passes == 0;
  uint32_t count = tiled ? static_cast<uint32_t>(tileCount(f) * TILE * TILE) : loop->liveCount;
  const uint32_t* live = loop->live;
  uint32_t* next = loop->next;
  int lane = static_cast<int>(threadIdx.x & 31);
  for (;;) {
    uint32_t base = 0;
    if (lane == 0) base = atomicAdd(&loop->cursor, 32u);
    base = __shfl_sync(0xffffffffu, base, 0);
    if (base >= count) return;
    uint32_t i = base + static_cast<uint32_t>(lane);
    int pixel = -1;
    if (i < count) pixel = tiled ? tiledPixel(f, static_cast<int>(i)) : static_cast<int>(live[i]);
    // graph resolves after its loop: writing the pixels here (FinishedRays) spilled in this
    // resident loop (80 -> 116 bytes of spill stores; graph's floors 2-3% slower, H200).
    bool stopped = renderRay(f, graphFrame.cache, graphFrame.pool, graphFrame.payload, pixel, tiled,
                             FinishedRays{}, WarpRays{&shared[threadIdx.x / WARP_SIZE]});
    appendStopped(stopped, static_cast<uint32_t>(pixel), next, &loop->nextCount);
  }
}

// The WHILE node's condition; none when the host drives the loop (GraphDriver::Host).
struct WhileCondition {
  cudaGraphConditionalHandle handle;
  bool exists;
};

__device__ void stopLoop(GraphLoop* loop, WhileCondition condition) {
  loop->stop = 1;
  if (condition.exists) cudaGraphSetConditional(condition.handle, 0);
}

__global__ void afterRenderKernel(const GraphFrame* frame, GraphLoop* loop,
                                  WhileCondition condition) {
  uint32_t* t = loop->live;
  loop->live = loop->next;
  loop->next = t;
  loop->liveCount = loop->nextCount;
  loop->nextCount = 0;
  loop->cursor = 0;
  ++loop->passes;
  if (loop->liveCount == 0) {
    stopLoop(loop, condition);
  } else {
    loop->failedBefore = frame->cache.counters[COUNTER_FAILED];
  }
}

__global__ void afterProduceKernel(const GraphFrame* frame, GraphLoop* loop,
                                   WhileCondition condition) {
  if (loop->stop) return;
  frame->cache.counters[COUNTER_REQUESTS] = 0;
  loop->cursor = 0;
  uint32_t exit = frame->cache.counters[COUNTER_FAILED] != loop->failedBefore ? GRAPH_FAILED
                  : loop->passes >= static_cast<uint32_t>(SP_MAX_PASSES)      ? GRAPH_MAX_PASSES
                                                                              : GRAPH_DONE;
  if (exit != GRAPH_DONE) {
    loop->exit = exit;
    stopLoop(loop, condition);
  }
}

}  // namespace

cudaGraphExec_t buildSpGraph(const GraphFrame* frame, GraphLoop* loop, GraphDriver driver,
                             const CudaProducerKernels& producer) {
  int renderBlocks = residentBlocks(graphRenderKernel, RENDER_BLOCK);
  cudaGraph_t graph = nullptr;
  GVDP_CUDA_CHECK(cudaGraphCreate(&graph, 0));
  WhileCondition condition{0, driver == GraphDriver::Device};
  cudaGraph_t body = graph;
  if (condition.exists) {
    GVDP_CUDA_CHECK(
        cudaGraphConditionalHandleCreate(&condition.handle, graph, 1, cudaGraphCondAssignDefault));
    cudaGraphNodeParams params{};
    params.type = cudaGraphNodeTypeConditional;
    params.conditional.handle = condition.handle;
    params.conditional.type = cudaGraphCondTypeWhile;
    params.conditional.size = 1;
    cudaGraphNode_t node = nullptr;
    GVDP_CUDA_CHECK(cudaGraphAddNode(&node, graph, nullptr, nullptr, 0, &params));
    body = params.conditional.phGraph_out[0];
  }

  cudaStream_t stream = nullptr;
  GVDP_CUDA_CHECK(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking));
  GVDP_CUDA_CHECK(cudaStreamBeginCaptureToGraph(stream, body, nullptr, nullptr, 0,
                                                cudaStreamCaptureModeRelaxed));
  graphRenderKernel<<<renderBlocks, RENDER_BLOCK, 0, stream>>>(frame, loop);
  afterRenderKernel<<<1, 1, 0, stream>>>(frame, loop, condition);
  producer.captureGraphProduce(frame, loop, stream);
  afterProduceKernel<<<1, 1, 0, stream>>>(frame, loop, condition);
  GVDP_CUDA_CHECK(cudaStreamEndCapture(stream, &body));
  GVDP_CUDA_CHECK(cudaStreamDestroy(stream));

  cudaGraphExec_t exec = nullptr;
  GVDP_CUDA_CHECK(cudaGraphInstantiate(&exec, graph, 0));
  GVDP_CUDA_CHECK(cudaGraphDestroy(graph));
  return exec;
}

}  // namespace gvdp::detail
