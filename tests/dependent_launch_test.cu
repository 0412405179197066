// Kernels launched with programmatic dependent launch (base/dependent_launch.cuh): the attribute
// is set only for code that waits in awaitPriorGrids (compute_90 or later), and a chain of such
// kernels still runs in stream order. Compiled only in a CUDA build; runs only with a device.
#include <gtest/gtest.h>

#include <iostream>
#include <vector>

#include "gvdp/base/dependent_launch.cuh"
#include "gvdp/base/gpu.h"
#include "gvdp/profile/parallel_for.cuh"
#include "test_util.h"

namespace gvdp::detail {
namespace {

__global__ void addOneAfterPriorGrids(uint32_t* values, uint32_t n) {
  awaitPriorGrids();
  releaseDependentGrids();
  for (uint32_t i = blockIdx.x * blockDim.x + threadIdx.x; i < n; i += gridDim.x * blockDim.x)
    values[i] += 1u;
}

// The same through parallelForCuda (an extended lambda needs a free function around it).
void addOneWithParallelFor(uint32_t* values, uint32_t n, cudaStream_t stream) {
  parallelForCuda("test: add one", stream, n, TimelineView{}, TaskKind::Cache,
                  [values] __device__(uint32_t i) { values[i] += 1u; });
}

// This build's kernels (GVDP_CUDA_ARCHITECTURES: 90) are launched early: with an older virtual
// architecture the attribute would be dropped and the frame's start would lose its overlap.
TEST(DependentLaunch, KernelsBuiltForHopperStartEarly) {
  GVDP_REQUIRE_GPU();
  cudaFuncAttributes a{};
  ASSERT_EQ(cudaFuncGetAttributes(&a, reinterpret_cast<const void*>(addOneAfterPriorGrids)),
            cudaSuccess);
  std::cout << "[ measure ] ptxVersion " << a.ptxVersion << ", binaryVersion " << a.binaryVersion
            << "\n";
  EXPECT_TRUE(awaitsPriorGrids(reinterpret_cast<const void*>(addOneAfterPriorGrids)));
}

// 64 kernels, each adding one to every value after the one before it: every value ends at 64
// (a kernel that read before the last one's writes were visible would lose an addition).
TEST(DependentLaunch, AChainOfKernelsRunsInStreamOrder) {
  GVDP_REQUIRE_GPU();
  constexpr uint32_t N = 1u << 20, KERNELS = 64;
  OwnedGpuStream stream(createGpuStream());
  DeviceBuffer<uint32_t> values(N);
  fillDevice(values.data(), 0, values.bytes(), stream.get());
  for (uint32_t k = 0; k < KERNELS; ++k) {
    if (k % 2)
      launchDependent(addOneAfterPriorGrids, 264, 256, stream.get(), values.data(), N);
    else
      addOneWithParallelFor(values.data(), N, stream.get());
  }
  std::vector<uint32_t> host(N);
  readDevice(host.data(), values.data(), values.bytes(), stream.get());
  for (uint32_t i = 0; i < N; ++i) ASSERT_EQ(host[i], KERNELS) << i;
}

}  // namespace
}  // namespace gvdp::detail
