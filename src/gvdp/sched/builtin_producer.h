// The kernels of the built-in scenes (world/scene.h: BuiltinScene), instantiated in the library
// once per world type (builtin_producer.cpp, compiled by nvcc in CUDA builds): a scene's kernels
// hold its world's code alone, with no switch over the five at each call.
#pragma once

#include "gvdp/sched/producer_kernels.h"
#include "gvdp/world/scene.h"

namespace gvdp::detail {

ProducerKernelsPtr builtinProducerKernels(const BuiltinScene& scene);

}  // namespace gvdp::detail
