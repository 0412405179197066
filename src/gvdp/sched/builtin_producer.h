// The kernels of the built-in scenes (world/scene.h: BuiltinScene), instantiated once in the
// library (builtin_producer.cpp, compiled by nvcc in CUDA builds).
#pragma once

#include "gvdp/sched/producer_kernels.h"
#include "gvdp/world/scene.h"

namespace gvdp::detail {

ProducerKernelsPtr builtinProducerKernels(const BuiltinScene& scene);

}  // namespace gvdp::detail
