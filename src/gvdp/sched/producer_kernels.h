// The producer-dependent steps of the schedulers behind one interface, so that the schedulers
// are compiled once, in the library, and a producer's code where its type is known: the
// implementation is ProducerKernelsOf<P> (producer_kernels_of.h), instantiated by
// include/gvdp/make_renderer.h in the user's translation unit, or by the library for the
// built-in scenes. Everything else a scheduler does (the march from the cache, the cache's
// maintenance, the loops) does not depend on the producer.
#pragma once

#include <cstdint>
#include <memory>

#include "gvdp/cache/brick_key.h"
#include "gvdp/cache/cache_view.h"
#include "gvdp/render/brick_pool.h"
#include "gvdp/render/frame.h"

namespace gvdp::detail {

class CudaProducerKernels;  // producer_kernels_cuda.h (CUDA builds)
struct ImportanceSetup;     // importance.h

class ProducerKernels {
 public:
  virtual ~ProducerKernels() = default;
  virtual float voxelSize0() const = 0;
  // CPU backend: Algorithm 2 for one brick on the calling worker (a ThreadScope), and the
  // direct renderer's frame into `pixels` on the thread pool.
  virtual void produceBrick(const CacheView& cache, const BrickPool& pool,
                            const BrickKey& key) const = 0;
  virtual void renderDirect(const FrameSetup& frame, uint32_t* pixels) const = 0;
  // The importance pre-pass of tiled frames (importance.h) on the thread pool.
  virtual void countBricks(const FrameSetup& frame, const ImportanceSetup& setup) const = 0;
  // CUDA backend: the kernels, or null when the producer's translation unit was not compiled
  // by nvcc (the CUDA backend then refuses it).
  virtual const CudaProducerKernels* cuda() const = 0;
};

using ProducerKernelsPtr = std::shared_ptr<const ProducerKernels>;

}  // namespace gvdp::detail
