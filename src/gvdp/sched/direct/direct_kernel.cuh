// CUDA kernel of the direct renderer: one thread per pixel in 8x8 tiles, same body as the CPU.
#pragma once

#include "gvdp/profile/timeline_device.cuh"
#include "gvdp/render/direct.h"

namespace gvdp::detail {

template <class P>
__global__ void directKernel(FrameSetup frame, P producer, uint32_t* image) {
  BlockTimer timer(frame.timeline, TaskKind::Render);
  int x = blockIdx.x * blockDim.x + threadIdx.x;
  int y = blockIdx.y * blockDim.y + threadIdx.y;
  if (x >= frame.width || y >= frame.height) return;
  int pixel = y * frame.width + x;
  image[pixel] = renderDirectPixel(frame, producer, pixel);
}

template <class P>
void launchDirectKernel(const FrameSetup& frame, const P& producer, uint32_t* image,
                        cudaStream_t stream) {
  dim3 block(8, 8);
  dim3 grid((frame.width + 7) / 8, (frame.height + 7) / 8);
  directKernel<<<grid, block, 0, stream>>>(frame, producer, image);
}

}  // namespace gvdp::detail
