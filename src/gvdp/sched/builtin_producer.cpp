#include "gvdp/sched/builtin_producer.h"

#include "gvdp/sched/producer_kernels_of.h"

#if GVDP_PRODUCER_CUDA
#include "gvdp/sched/pt_noise_workers.h"
#endif

namespace gvdp::detail {

#if GVDP_PRODUCER_CUDA
#define GVDP_ELSEWHERE(W) GVDP_PT_WORKERS_OF(extern template, W)
GVDP_NOISE_WORLDS(GVDP_ELSEWHERE)
#undef GVDP_ELSEWHERE
#endif

// The kernels of the scene's own world type. Those of BuiltinScene switched over the five worlds
// at every call: pt's worker was 31 272 SASS instructions against 14 784-20 312 for one world
// (sm_90), and a world's own kernels gave pt +5.0% FPS (H100, 25 cells; docs/DESIGN.md).
ProducerKernelsPtr builtinProducerKernels(const BuiltinScene& scene) {
  return scene.visit([](const auto& world) { return makeProducerKernels(world); });
}

}  // namespace gvdp::detail
