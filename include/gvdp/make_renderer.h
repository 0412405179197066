// makeRenderer for your own world: a producer type (gvdp/producer.h) whose kernels are
// instantiated here, in your translation unit. Compile it with nvcc (a .cu file, or
// LANGUAGE CUDA) for the cuda backend, and with relocatable device code
// (CUDA_SEPARABLE_COMPILATION) for the dp scheduler there; a C++ compiler gives the CPU backend.
#pragma once

#include <memory>

#include "gvdp/producer.h"
#include "gvdp/renderer.h"
#include "gvdp/sched/producer_kernels_of.h"

namespace gvdp {

template <Producer P>
std::unique_ptr<Renderer> makeRenderer(const P& producer, const RendererOptions& options) {
  return std::make_unique<Renderer>(options, detail::makeProducerKernels(producer));
}

}  // namespace gvdp
