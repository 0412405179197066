// ProducerKernels for a producer type P: the CPU steps always, the CUDA kernels when this
// translation unit is compiled by nvcc for a CUDA build of gvdp, dp's kernels only with
// relocatable device code (their device-side launches need it) and GVDP_CDP.
#pragma once

#include "gvdp/base/parallel.h"
#include "gvdp/cache/produce.h"
#include "gvdp/render/direct.h"
#include "gvdp/sched/importance.h"
#include "gvdp/sched/producer_kernels.h"
#include "gvdp/world/producer.h"

#if GVDP_HAS_CUDA && defined(__CUDACC__)
#define GVDP_PRODUCER_CUDA 1
#include "gvdp/sched/direct/direct_kernel.cuh"
#include "gvdp/sched/graph/graph_produce.cuh"
#include "gvdp/sched/importance_kernel.cuh"
#include "gvdp/sched/producer_kernels_cuda.h"
#include "gvdp/sched/pt/pt_worker.cuh"
#include "gvdp/sched/sp/sp_produce.cuh"
#if GVDP_CDP && defined(__CUDACC_RDC__)
#define GVDP_PRODUCER_DP 1
#include "gvdp/sched/dp/dp_kernels.cuh"
#endif
#endif

// The classes differ with the mode (CUDA, dp): an inline namespace per mode keeps translation
// units of different modes from defining one name twice.
#if GVDP_PRODUCER_DP
#define GVDP_PRODUCER_MODE producer_cuda_dp
#elif GVDP_PRODUCER_CUDA
#define GVDP_PRODUCER_MODE producer_cuda
#else
#define GVDP_PRODUCER_MODE producer_host
#endif

namespace gvdp::detail {
inline namespace GVDP_PRODUCER_MODE {

#if GVDP_PRODUCER_CUDA
template <Producer P>
class CudaProducerKernelsOf final : public CudaProducerKernels {
 public:
  explicit CudaProducerKernelsOf(const P& producer) : p_(producer) {}

  void launchDirect(const FrameSetup& frame, uint32_t* image, cudaStream_t stream) const override {
    launchDirectKernel(frame, p_, image, stream);
  }
  void launchCountBricks(const FrameSetup& frame, const ImportanceSetup& setup,
                         cudaStream_t stream) const override {
    launchCountBricksKernel(frame, p_, setup, stream);
  }
  void launchProduce(const FrameSetup& frame, const CacheView& cache, const BrickPool& pool,
                     uint32_t requests, cudaStream_t stream) const override {
    launchProduceKernel(frame, cache, pool, p_, requests, stream);
  }
  void captureGraphProduce(const GraphFrame* frame, GraphLoop* loop,
                           cudaStream_t stream) const override {
    captureGraphProduceKernel(frame, loop, p_, stream);
  }
  int ptWorkerBlocks() const override { return ptWorkerBlocksOf<P>(); }
  void launchPtFrame(const PtContext& ctx, const BrickPool& pool, int blocks,
                     cudaStream_t stream) const override {
    launchPtWorkers(ctx, pool, p_, blocks, stream);
  }
#if GVDP_PRODUCER_DP
  bool hasDp() const override {
    return true;
  }
  void launchDpFrame(const DpContext* deviceContext, const FrameSetup& frame,
                     cudaStream_t stream) const override {
    launchDpRoot(deviceContext, frame, p_, stream);
  }
#else
  bool hasDp() const override {
    return false;
  }
  void launchDpFrame(const DpContext*, const FrameSetup&, cudaStream_t) const override {}
#endif

 private:
  P p_;
};
#endif

template <Producer P>
class ProducerKernelsOf final : public ProducerKernels {
 public:
  explicit ProducerKernelsOf(const P& producer)
      : p_(producer)
#if GVDP_PRODUCER_CUDA
        ,
        cuda_(producer)
#endif
  {
  }

  float voxelSize0() const override {
    return p_.voxelSize0();
  }
  void produceBrick(const CacheView& cache, const BrickPool& pool,
                    const BrickKey& key) const override {
    detail::produceBrick<BRICK_SAMPLE_COUNT>(ThreadScope{}, p_, cache, pool, key);
  }
  void renderDirect(const FrameSetup& frame, uint32_t* pixels) const override {
    parallelFor(
        frame.pixelCount(),
        [&](int64_t i) { pixels[i] = renderDirectPixel(frame, p_, static_cast<int>(i)); }, 16);
  }
  void countBricks(const FrameSetup& frame, const ImportanceSetup& setup) const override {
    parallelFor(
        setup.rays(),
        [&](int64_t i) { countRayBricks(frame, p_, setup, static_cast<uint32_t>(i)); }, 16);
    parallelFor(
        setup.status[IMPORTANCE_BRICKS],
        [&](int64_t i) {
          uint64_t slot = setup.bricks[i];
          BrickKey brick = importanceBrick(frame, setup.table[slot]);
          uint8_t occupied = 0;
          for (int k = 0; k < BRICK_SAMPLE_COUNT && !occupied; ++k)
            occupied = importanceSampleOccupied(p_, brick, k) ? 1 : 0;
          setup.occupied[slot] = occupied;
        },
        16);
    auto slots = static_cast<int64_t>(setup.tableSize());
    parallelFor(
        slots, [&](int64_t i) { countImportanceNode(setup, static_cast<uint64_t>(i)); }, 4096);
  }
#if GVDP_PRODUCER_CUDA
  const CudaProducerKernels* cuda() const override {
    return &cuda_;
  }
#else
  const CudaProducerKernels* cuda() const override {
    return nullptr;
  }
#endif

 private:
  P p_;
#if GVDP_PRODUCER_CUDA
  CudaProducerKernelsOf<P> cuda_;
#endif
};

template <Producer P>
ProducerKernelsPtr makeProducerKernels(const P& producer) {
  return std::make_shared<ProducerKernelsOf<P>>(producer);
}

}  // namespace GVDP_PRODUCER_MODE
}  // namespace gvdp::detail
