#include "gvdp/sched/builtin_producer.h"

#include "gvdp/sched/producer_kernels_of.h"

namespace gvdp::detail {

ProducerKernelsPtr builtinProducerKernels(const BuiltinScene& scene) {
  return makeProducerKernels(scene);
}

}  // namespace gvdp::detail
