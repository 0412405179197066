// Launcher of the pt rings' initialisation (pt_kernels.cu); the worker kernel is launched
// through CudaProducerKernels (pt_worker.cuh).
#pragma once

#include <cuda_runtime_api.h>

#include "gvdp/sched/pt/pt_body.h"

namespace gvdp::detail {

// Empties the ray and task rings and fills the free task-id rings (pt_body.h: PtLayout).
void launchPtRingsInit(const PtContext& ctx, const PtLayout& layout, cudaStream_t stream);

}  // namespace gvdp::detail
