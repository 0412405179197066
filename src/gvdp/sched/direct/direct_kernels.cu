// CUDA kernel of the direct renderer: one thread per pixel in 8x8 tiles, same body as the CPU.
#include "gvdp/profile/timeline_device.cuh"
#include "gvdp/render/direct.h"
#include "gvdp/sched/direct/direct_cuda.h"

namespace gvdp {

__global__ void directKernel(FrameSetup frame, uint32_t* image) {
  BlockTimer timer(TaskKind::Render);
  int x = blockIdx.x * blockDim.x + threadIdx.x;
  int y = blockIdx.y * blockDim.y + threadIdx.y;
  if (x >= frame.width || y >= frame.height) return;
  int pixel = y * frame.width + x;
  image[pixel] = renderDirectPixel(frame, pixel);
}

void launchDirect(const FrameSetup& frame, uint32_t* image, cudaStream_t stream) {
  dim3 block(8, 8);
  dim3 grid((frame.width + 7) / 8, (frame.height + 7) / 8);
  directKernel<<<grid, block, 0, stream>>>(frame, image);
}

}  // namespace gvdp
