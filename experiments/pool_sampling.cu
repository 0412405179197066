// Experiment (issue 13, "measure the sampling path"): the pool read as the march reads it today
// (a slot-major array through L1, software trilinear) against a 3D texture holding the same
// samples, on the render floor (a frame rendered again from a full cache: every brick resident).
//
// Renders frames 0..N of a scene's walkthrough with sp on the GPU, then times frame N's first
// render pass again four ways (CUDA events, median of 21 after 3 warm-up
// launches, every launch the same rays over the same cache):
//   array       BrickPool<ReadOnly>: ld.global.nc, 8 loads, trilinear() - what sp runs;
//   tex-point   the pool copied into a 3D cudaArray (bricks on a grid), 8 point fetches,
//               the same trilinear(): the same image by construction;
//   tex-linear  the same cudaArray, one hardware-filtered fetch (weights with 8 fractional
//               bits): a different image;
// and prints each variant's image against array's (pixels that differ, PSNR).
// Only a frame whose pool no kernel writes may read a texture (its cache is coherent at kernel
// boundaries only), so these numbers concern sp and graph; dp and pt read the array.
//
// Usage: gvdp_pool_sampling [scene] [width] [height] [frame]   (default perlin 1500 1000 30)
#include <cuda_runtime.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "experiment_main.h"
#include "gvdp/base/image.h"
#include "gvdp/bench/sequence.h"
#include "gvdp/mesh/text_tokens.h"
#include "gvdp/sched/builtin_producer.h"
#include "gvdp/sched/ray_tasks.h"
#include "gvdp/sched/sp/sp_cuda.h"
#include "gvdp/sched/sp/sp_loop_cuda.h"

namespace gvdp::detail {
namespace {

// The pool's slots as 10^3 blocks of a 3D array: slot s at block (s % nx, s / nx % ny, s / nx /
// ny).
struct BrickGrid {
  int nx, ny, nz;
  GVDP_HD Vec3i block(uint32_t slot) const {
    int s = static_cast<int>(slot);
    return {s % nx * BRICK_SAMPLES, s / nx % ny * BRICK_SAMPLES, s / (nx * ny) * BRICK_SAMPLES};
  }
};

template <bool HARDWARE_FILTER>
struct TexturePool {
  cudaTextureObject_t tex;  // point: uchar4 elements; linear: normalised floats
  const uint64_t* occupancy;
  BrickGrid grid;

  template <PoolReads>
  __device__ uint64_t loadOccupancy(uint32_t slot) const {
    return __ldg(reinterpret_cast<const unsigned long long*>(occupancy + slot));
  }

  // Voxel index i of the brick at `origin` is texel block + 1 + (i - origin), whose centre is
  // at texel coordinate + 0.5, as voxel i's is at v = i + 0.5. A sample in a clear cell of
  // `cells` is zero without a fetch, as the array's (BrickPool::sample).
  template <PoolReads>
  __device__ Vec4f sample(uint32_t slot, Vec3i origin, Vec3f v, uint64_t cells) const {
    Vec3i first = trilinearSite(v).first;
    if (!(cells & occupancyBitOfBlock(
                      {first.x - origin.x + 1, first.y - origin.y + 1, first.z - origin.z + 1})))
      return {0.0f, 0.0f, 0.0f, 0.0f};
    Vec3i b = grid.block(slot);
    Vec3f shift{static_cast<float>(b.x + 1 - origin.x), static_cast<float>(b.y + 1 - origin.y),
                static_cast<float>(b.z + 1 - origin.z)};
    if constexpr (HARDWARE_FILTER) {
      float4 c = tex3D<float4>(tex, v.x + shift.x, v.y + shift.y, v.z + shift.z);
      return {c.x, c.y, c.z, c.w};
    } else {
      Vec3i s{b.x + 1 - origin.x, b.y + 1 - origin.y, b.z + 1 - origin.z};
      return trilinear(v, [&](Vec3i i) {
        return [&, i](int dx, int dy, int dz) {
          int x = i.x + dx, y = i.y + dy, z = i.z + dz;
          uchar4 c =
              tex3D<uchar4>(tex, static_cast<float>(x + s.x) + 0.5f,
                            static_cast<float>(y + s.y) + 0.5f, static_cast<float>(z + s.z) + 0.5f);
          return Rgba8{c.x} | Rgba8{c.y} << 8 | Rgba8{c.z} << 16 | Rgba8{c.w} << 24;
        };
      });
    }
  }
};

__global__ void copyToArrayKernel(const Rgba8* texels, uint32_t slots, BrickGrid grid,
                                  cudaSurfaceObject_t surf) {
  uint64_t i = blockIdx.x * uint64_t{blockDim.x} + threadIdx.x;
  if (i >= uint64_t{slots} * BRICK_SAMPLE_COUNT) return;
  uint32_t slot = static_cast<uint32_t>(i / BRICK_SAMPLE_COUNT);
  int s = static_cast<int>(i % BRICK_SAMPLE_COUNT);
  Vec3i b = grid.block(slot);
  Rgba8 v = texels[i];
  uchar4 c = make_uchar4(v & 255u, v >> 8 & 255u, v >> 16 & 255u, v >> 24);
  surf3Dwrite(c, surf, (b.x + s % BRICK_SAMPLES) * 4, b.y + s / BRICK_SAMPLES % BRICK_SAMPLES,
              b.z + s / (BRICK_SAMPLES * BRICK_SAMPLES));
}

// sp's first render pass (sp_kernels.cu) over any pool, without its timeline and stop list;
// MIN_BLOCKS > 0 caps the registers for that many blocks of 128 threads per SM.
template <class Pool, int MIN_BLOCKS = 0>
__global__ void __launch_bounds__(128, MIN_BLOCKS)
    firstPassKernel(FrameSetup f, CacheView cache, Pool pool, RayState* payload,
                    uint32_t* stopped) {
  int pixel = tiledPixel(f, static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x));
  if (pixel < 0) return;
  if (renderRay(f, cache, pool, payload, pixel, true, FinishedRays{})) atomicAdd(stopped, 1u);
}

struct Timing {
  double medianMs;
  uint32_t stopped;
  Image image;
};

class SamplingExperiment final : public SpFrameCuda {
 public:
  SamplingExperiment(const SchedulerOptions& o, ProducerKernelsPtr p)
      : SpFrameCuda(o, std::move(p)), slots_(poolBricksOf(o)) {}
  ~SamplingExperiment() override { release(); }

  // `frame`: sp's image of f, which array's must equal.
  void measure(const FrameSetup& f, const Image& frame) {
    copyPool();
    TexturePool<false> point{point_, cache_.pool().occupancy, grid_};
    Timing array = time<BrickPool, 0>(f, cache_.pool());
    report("array", firstPassKernel<BrickPool, 0>, array, array);
    std::printf("  array's image %s sp's frame\n",
                array.image.pixels == frame.pixels ? "equals" : "DIFFERS FROM");
    report("tex-point", firstPassKernel<TexturePool<false>, 0>,
           time<TexturePool<false>, 0>(f, point), array);
    report("tex-point-64", firstPassKernel<TexturePool<false>, 8>,
           time<TexturePool<false>, 8>(f, point), array);
    // Last: its rays may go further (other opacities) and claim bricks no one produces.
    report(
        "tex-linear", firstPassKernel<TexturePool<true>, 0>,
        time<TexturePool<true>, 0>(f, TexturePool<true>{linear_, cache_.pool().occupancy, grid_}),
        array);
  }

 private:
  void renderFrame(const FrameSetup& f, Image&, FrameStats& stats) override {
    cache_.beginFrame(f);
    runSpLoopCuda(f, cudaProducer(), cache_, buffers_, 0, true, stats, stream());
    resolveCuda(f, buffers_, stream());  // its unfinished pixels counted by finishFrame
  }

  void copyPool() {
    if (!array_) {
      int n = 1;
      while (n * n * n < static_cast<int>(slots_)) ++n;
      grid_ = {n, n, (static_cast<int>(slots_) + n * n - 1) / (n * n)};
      cudaChannelFormatDesc desc = cudaCreateChannelDesc<uchar4>();
      cudaExtent extent = make_cudaExtent(static_cast<size_t>(grid_.nx) * BRICK_SAMPLES,
                                          static_cast<size_t>(grid_.ny) * BRICK_SAMPLES,
                                          static_cast<size_t>(grid_.nz) * BRICK_SAMPLES);
      GVDP_CUDA_CHECK(cudaMalloc3DArray(&array_, &desc, extent, cudaArraySurfaceLoadStore));
      cudaResourceDesc res{};
      res.resType = cudaResourceTypeArray;
      res.res.array.array = array_;
      GVDP_CUDA_CHECK(cudaCreateSurfaceObject(&surf_, &res));
      cudaTextureDesc td{};
      td.addressMode[0] = td.addressMode[1] = td.addressMode[2] = cudaAddressModeClamp;
      td.filterMode = cudaFilterModePoint;
      td.readMode = cudaReadModeElementType;
      GVDP_CUDA_CHECK(cudaCreateTextureObject(&point_, &res, &td, nullptr));
      td.filterMode = cudaFilterModeLinear;
      td.readMode = cudaReadModeNormalizedFloat;
      GVDP_CUDA_CHECK(cudaCreateTextureObject(&linear_, &res, &td, nullptr));
      GVDP_CUDA_CHECK(cudaMalloc(&stopped_, sizeof(uint32_t)));
    }
    uint64_t n = uint64_t{slots_} * BRICK_SAMPLE_COUNT;
    copyToArrayKernel<<<static_cast<unsigned>((n + 255) / 256), 256, 0, stream()>>>(
        cache_.pool().texels, slots_, grid_, surf_);
    GVDP_CUDA_CHECK(cudaGetLastError());
    GVDP_CUDA_CHECK(cudaStreamSynchronize(stream()));
  }

  template <class Kernel>
  static void report(const char* name, Kernel kernel, const Timing& t, const Timing& array) {
    cudaFuncAttributes a{};
    GVDP_CUDA_CHECK(cudaFuncGetAttributes(&a, kernel));
    int64_t differ = 0;
    for (size_t i = 0; i < t.image.pixels.size(); ++i)
      differ += t.image.pixels[i] != array.image.pixels[i];
    std::printf(
        "  %-12s %3d registers  %7.3f ms  %.2fx  %lld pixels differ (PSNR %.1f dB), "
        "%u rays stopped\n",
        name, a.numRegs, t.medianMs, array.medianMs / t.medianMs, static_cast<long long>(differ),
        psnr(array.image, t.image), t.stopped);
    std::fflush(stdout);
  }

  template <class Pool, int MIN_BLOCKS>
  Timing time(const FrameSetup& f, const Pool& pool) {
    unsigned items = static_cast<unsigned>(tileCount(f) * TILE * TILE);
    CacheView view = cache_.view();
    auto launch = [&] {
      firstPassKernel<Pool, MIN_BLOCKS><<<(items + 127) / 128, 128, 0, stream()>>>(
          f, view, pool, buffers_.payload.data(), stopped_);
    };
    for (int i = 0; i < 3; ++i) launch();
    cudaEvent_t start, stop;
    GVDP_CUDA_CHECK(cudaEventCreate(&start));
    GVDP_CUDA_CHECK(cudaEventCreate(&stop));
    std::vector<float> ms;
    for (int i = 0; i < 21; ++i) {
      GVDP_CUDA_CHECK(cudaEventRecord(start, stream()));
      launch();
      GVDP_CUDA_CHECK(cudaEventRecord(stop, stream()));
      GVDP_CUDA_CHECK(cudaEventSynchronize(stop));
      float t = 0;
      GVDP_CUDA_CHECK(cudaEventElapsedTime(&t, start, stop));
      ms.push_back(t);
    }
    GVDP_CUDA_CHECK(cudaEventDestroy(start));
    GVDP_CUDA_CHECK(cudaEventDestroy(stop));
    std::nth_element(ms.begin(), ms.begin() + 10, ms.end());
    Timing t{ms[10], 0, {}};
    GVDP_CUDA_CHECK(cudaMemsetAsync(stopped_, 0, sizeof(uint32_t), stream()));
    launch();
    GVDP_CUDA_CHECK(cudaGetLastError());
    readDevice(&t.stopped, stopped_, sizeof(uint32_t), stream());
    resolveCuda(f, buffers_, stream());
    downloadImage(f, buffers_, t.image, stream());
    return t;
  }

  void release() {
    if (!array_) return;
    cudaDestroyTextureObject(point_);
    cudaDestroyTextureObject(linear_);
    cudaDestroySurfaceObject(surf_);
    cudaFreeArray(array_);
    cudaFree(stopped_);
  }

  uint32_t slots_;
  BrickGrid grid_{};
  cudaArray_t array_ = nullptr;
  cudaSurfaceObject_t surf_ = 0;
  cudaTextureObject_t point_ = 0, linear_ = 0;
  uint32_t* stopped_ = nullptr;
};

int run(int argc, char** argv) {
  SequenceOptions o;
  o.scene = argc > 1 ? argv[1] : "perlin";
  auto number = [&](int i, const char* name, int fallback, int64_t lo) {
    int64_t v = fallback;
    if (argc > i && (!parseInt(argv[i], v) || v < lo || v > 100000))
      throw InputError(concat("bad ", name, " '", argv[i], "' (expected ", lo, "..100000)"));
    return static_cast<int>(v);
  };
  o.width = number(2, "width", 1500, 1);
  o.height = number(3, "height", 1000, 1);
  int at = number(4, "frame", 30, 0);
  o.scheduler.backend = Backend::Cuda;
  o.scheduler = resolvedOptions(o.scheduler);
  validate(o);
  checkResources(o);
  const SceneInfo& scene = findScene(o.scene);
  SamplingExperiment sp(o.scheduler, builtinProducerKernels(scene.world));
  std::printf(
      "%s %dx%d walkthrough frame %d (sp, pool %u bricks): the first render pass again, "
      "from a full cache\n",
      o.scene.c_str(), o.width, o.height, at, o.scheduler.poolBricks);
  Image image;
  for (int frame = 0; frame <= at; ++frame) {
    FrameSetup f = frameOf(o, frame);
    FrameStats stats = sp.render(f, &image);
    if (stats.unfinishedPixels != 0 || stats.degraded) {
      std::fprintf(stderr, "frame %d: unfinished %lld, degraded %d\n", frame,
                   static_cast<long long>(stats.unfinishedPixels), stats.degraded ? 1 : 0);
      return 1;
    }
    if (frame == at) sp.measure(f, image);
  }
  return 0;
}

}  // namespace
}  // namespace gvdp::detail

int main(int argc, char** argv) {
  return gvdp::detail::experimentMain("gvdp_pool_sampling", gvdp::detail::run, argc, argv);
}
