// Launcher of the CUDA direct renderer (kernel in direct_kernels.cu).
#pragma once

#include <cuda_runtime_api.h>

#include "gvdp/render/frame.h"

namespace gvdp {

void launchDirect(const FrameSetup& frame, uint32_t* image, cudaStream_t stream);

}  // namespace gvdp
