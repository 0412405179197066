// The importance pre-pass on the device: the table and the counts in device memory, the
// producer's kernel, the counts and the status words back.
#include "gvdp/base/cuda_util.h"
#include "gvdp/sched/importance_map.h"
#include "gvdp/sched/producer_kernels_cuda.h"

namespace gvdp::detail {

ImportanceStatus countBricksOnDevice(const ProducerKernels& producer, const FrameSetup& frame,
                                     uint64_t tableEntries, GpuStream stream, ImportanceMap& m) {
  const CudaProducerKernels* cuda = producer.cuda();
  GVDP_INPUT_CHECK(cuda != nullptr, "this producer has no CUDA kernels (compile it with nvcc)");
  DeviceBuffer<uint64_t> table(tableEntries);
  DeviceBuffer<uint8_t> occupied(tableEntries);
  DeviceBuffer<uint64_t> bricks(tableEntries);
  DeviceBuffer<uint32_t> counts(mipmapSize(m.levels));
  DeviceBuffer<uint32_t> status(IMPORTANCE_STATUS_WORDS);
  fillDevice(table.data(), 0xff, table.bytes(), stream);
  fillDevice(counts.data(), 0, counts.bytes(), stream);
  fillDevice(status.data(), 0, status.bytes(), stream);
  ImportanceSetup s = importanceSetup(m, frame, tableEntries);
  s.table = table.data();
  s.occupied = occupied.data();
  s.bricks = bricks.data();
  s.counts = counts.data();
  s.status = status.data();
  cuda->launchCountBricks(frame, s, stream);
  GVDP_CUDA_CHECK(cudaGetLastError());
  m.counts.resize(counts.size());
  ImportanceStatus out{};
  readDevice(m.counts.data(), counts.data(), counts.bytes(), stream);
  readDevice(out.data(), status.data(), status.bytes(), stream);
  return out;
}

}  // namespace gvdp::detail
