// The CUDA half of ProducerKernels: one launcher per producer-dependent kernel of the schedulers
// (their bodies: sched/*/…_produce.cuh, pt_worker.cuh, dp_kernels.cuh, direct_kernel.cuh), each on
// the scheduler's stream.
#pragma once

#include <cuda_runtime_api.h>

#include "gvdp/sched/dp/dp_body.h"
#include "gvdp/sched/graph/graph_frame.h"
#include "gvdp/sched/importance.h"
#include "gvdp/sched/producer_kernels.h"
#include "gvdp/sched/pt/pt_context.h"

namespace gvdp::detail {

class CudaProducerKernels {
 public:
  virtual ~CudaProducerKernels() = default;
  // direct: one thread per pixel into `image`.
  virtual void launchDirect(const FrameSetup& frame, uint32_t* image,
                            cudaStream_t stream) const = 0;
  // The importance pre-pass of tiled frames (importance.h): one thread per pre-pass ray.
  virtual void launchCountBricks(const FrameSetup& frame, const ImportanceSetup& setup,
                                 cudaStream_t stream) const = 0;
  // sp: Algorithm 2, one block per queued request.
  virtual void launchProduce(const FrameSetup& frame, const CacheView& cache, const BrickPool& pool,
                             uint32_t requests, cudaStream_t stream) const = 0;
  // graph: the production node, captured into `stream` (resident blocks claiming requests).
  virtual void captureGraphProduce(const GraphFrame* frame, GraphLoop* loop,
                                   cudaStream_t stream) const = 0;
  // pt: the persistent kernel's resident blocks, and the frame.
  virtual int ptWorkerBlocks() const = 0;
  virtual void launchPtFrame(const PtContext& ctx, const BrickPool& pool, int blocks,
                             cudaStream_t stream) const = 0;
  // dp: the root grid over the context in device memory (its launches do the rest); false when
  // the producer's translation unit has no relocatable device code (CDP needs it).
  virtual bool hasDp() const = 0;
  virtual void launchDpFrame(const DpContext* deviceContext, const FrameSetup& frame,
                             cudaStream_t stream) const = 0;
};

}  // namespace gvdp::detail
