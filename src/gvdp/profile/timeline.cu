// The device-side timeline buffer's symbol and its host-side switch.
#include "gvdp/profile/timeline_cuda.h"
#include "gvdp/profile/timeline_device.cuh"

namespace gvdp {

__device__ TimelineView deviceTimeline;

void setDeviceTimeline(const TimelineView& view) {
  cudaMemcpyToSymbol(deviceTimeline, &view, sizeof view);
}

}  // namespace gvdp
