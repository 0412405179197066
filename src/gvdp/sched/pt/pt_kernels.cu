// The pt rings' initialisation kernel (the worker kernel: pt_worker.cuh).
#include "gvdp/sched/pt/pt_cuda.h"

namespace gvdp::detail {
namespace {

__global__ void ringInitKernel(Ring ring, uint32_t filled) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i <= ring.mask) ring.slots[i] = ringInitialSlot(i, filled);
}

void initRing(const Ring& ring, uint32_t filled, cudaStream_t stream) {
  uint32_t n = ring.mask + 1;
  ringInitKernel<<<(n + 255) / 256, 256, 0, stream>>>(ring, filled);
}

}  // namespace

void launchPtRingsInit(const PtContext& ctx, const PtLayout& layout, cudaStream_t stream) {
  initRing(ctx.rays, 0, stream);
  initRing(ctx.tasks, 0, stream);
  initRing(ctx.freeIds, layout.freeIds(), stream);
  initRing(ctx.lookaheadIds, PT_LOOKAHEAD_IDS, stream);
  initRing(ctx.prefetchIds, PT_PREFETCH_IDS, stream);
}

}  // namespace gvdp::detail
