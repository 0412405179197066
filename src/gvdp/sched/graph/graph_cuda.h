// The sp loop as one CUDA graph (graph_kernels.cu): a conditional WHILE node whose body is
// render pass -> swap the live-ray lists -> production -> clear the requests, with the loop's
// state in device memory, so a frame is one graph launch and one read-back.
#pragma once

#include <cuda_runtime_api.h>

#include "gvdp/sched/graph/graph.h"
#include "gvdp/sched/graph/graph_frame.h"

namespace gvdp::detail {

class CudaProducerKernels;

// Builds and instantiates the graph for this device; its kernels read *frame (uploaded before
// each launch) and *loop.
cudaGraphExec_t buildSpGraph(const GraphFrame* frame, GraphLoop* loop, GraphDriver driver,
                             const CudaProducerKernels& producer);

}  // namespace gvdp::detail
