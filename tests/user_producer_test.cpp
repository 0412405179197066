// A world the library does not know: the gyroid of examples/custom_producer, instantiated here
// (compiled by nvcc in a CUDA build, so that its GPU kernels exist in this translation unit).
// Every scheduler renders the same frames of it, bit for bit, and its emptiness bound is sound.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#if GVDP_HAS_CUDA && defined(__CUDACC__)
#include <cuda_runtime.h>
#endif

#include "../examples/custom_producer/gyroid.h"
#include "gvdp/base/clock.h"
#include "gvdp/base/error.h"
#include "gvdp/make_renderer.h"
#include "gvdp/world/scene.h"
#include "test_util.h"

namespace gvdp::detail {
namespace {

constexpr Gyroid GYROID{4.0f, 2.0f, 0.3f, 0.005f};

// A short walk towards the ball, turning a little.
CameraPose poseAt(int frame) {
  return {{0.0, 0.5, -9.0 + 0.2 * frame}, 0.02f * frame, 0.0f};
}

struct Frames {
  std::vector<Image> images;
  std::vector<FrameStats> stats;
};

template <class P>
Frames renderFrames(const P& producer, Backend backend, SchedulerKind kind, int frames) {
  RendererOptions o;
  o.scheduler.backend = backend;
  o.scheduler.kind = kind;
  o.width = 96;
  o.height = 64;
  std::unique_ptr<Renderer> r = makeRenderer(producer, o);
  Frames out;
  for (int f = 0; f < frames; ++f) {
    out.images.emplace_back();
    out.stats.push_back(r->render(poseAt(f), out.images.back()));
  }
  EXPECT_EQ(r->frames(), frames);
  return out;
}

void expectSameFrames(const Frames& a, const Frames& b, const char* what) {
  ASSERT_EQ(a.images.size(), b.images.size());
  for (size_t f = 0; f < a.images.size(); ++f) {
    EXPECT_EQ(a.images[f].pixels, b.images[f].pixels) << what << " frame " << f;
    EXPECT_EQ(b.stats[f].unfinishedPixels, 0) << what << " frame " << f;
  }
}

}  // namespace

TEST(UserProducer, EverySchedulerRendersTheSameGyroidOnTheCpu) {
  Frames sp = renderFrames(GYROID, Backend::Cpu, SchedulerKind::Sp, 4);
  EXPECT_GT(sp.stats[0].cache.produced, 0u);
  expectSameFrames(sp, renderFrames(GYROID, Backend::Cpu, SchedulerKind::Dp, 4), "dp");
  expectSameFrames(sp, renderFrames(GYROID, Backend::Cpu, SchedulerKind::Pt, 4), "pt");
  Frames direct = renderFrames(GYROID, Backend::Cpu, SchedulerKind::Direct, 4);
  for (size_t f = 0; f < sp.images.size(); ++f) {
    double db = psnr(sp.images[f], direct.images[f]);
    std::printf("[ measure ] gyroid frame %zu sp vs direct (cpu, 96x64): PSNR %.2f dB\n", f, db);
    EXPECT_GE(db, 45.0) << "frame " << f;
  }
}

// The gyroid with no per-voxel empty flags: only its box bound can make a brick EMPTY.
struct GyroidBoundOnly {
  Gyroid g;
  GVDP_HD VoxelSample voxel(Vec3d p, float voxelSize) const {
    return {g.voxel(p, voxelSize).rgba, false};
  }
  GVDP_HD bool emptyBox(Vec3d lo, Vec3d hi, float v) const { return g.emptyBox(lo, hi, v); }
  GVDP_HD float voxelSize0() const { return g.voxelSize0(); }
};

// The emptiness bound makes whole bricks EMPTY without a voxel evaluated, and changes no pixel.
TEST(UserProducer, EmptinessBoundMakesEmptyBricksAndTheSameImage) {
  Frames flags = renderFrames(GYROID, Backend::Cpu, SchedulerKind::Sp, 2);
  Frames bound = renderFrames(GyroidBoundOnly{GYROID}, Backend::Cpu, SchedulerKind::Sp, 2);
  EXPECT_GT(bound.stats[0].cache.empty, 0u);
  expectSameFrames(flags, bound, "bound only");
}

// emptyBox is conservative: inside a box it clears, every voxel of that size is flagged empty.
TEST(UserProducer, EmptyBoxIsConservative) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(-20.0, 20.0), size(0.01, 2.0), unit(0.0, 1.0);
  int cleared = 0;
  for (int i = 0; i < 20000; ++i) {
    Vec3d lo{pos(rng), pos(rng), pos(rng)};
    double s = size(rng);
    Vec3d hi{lo.x + s, lo.y + s, lo.z + s};
    float voxelSize = static_cast<float>(s / 8.0);
    if (!GYROID.emptyBox(lo, hi, voxelSize)) continue;
    ++cleared;
    for (int k = 0; k < 8; ++k) {
      Vec3d p{lo.x + s * unit(rng), lo.y + s * unit(rng), lo.z + s * unit(rng)};
      VoxelSample v = GYROID.voxel(p, voxelSize);
      ASSERT_TRUE(v.empty && v.rgba == 0u) << "box " << i << " point " << k;
    }
  }
  EXPECT_GT(cleared, 100) << "the bound should clear some boxes";
}

// A built-in world's own producer type through the template path renders what the built-in
// scene of the same name renders.
TEST(UserProducer, PerlinAsAUserProducerMatchesTheBuiltinScene) {
  RendererOptions o;
  o.width = 64;
  o.height = 40;
  const SceneInfo& perlin = findScene("perlin");
  std::unique_ptr<Renderer> builtin = makeRenderer("perlin", o);
  std::unique_ptr<Renderer> user =
      makeRenderer(PerlinWorld{perlin.world.finest, perlin.world.seed}, o);
  for (int f = 0; f < 2; ++f) {
    CameraPose pose = perlin.start;
    pose.position.z += perlin.speed * f;
    Image a, b;
    builtin->render(pose, a);
    user->render(pose, b);
    EXPECT_EQ(a.pixels, b.pixels) << "frame " << f;
  }
}

TEST(UserProducer, RendererRefusesBadOptionsAndProducers) {
  RendererOptions o;
  o.width = 3;
  EXPECT_THROW(makeRenderer(GYROID, o), InputError);
  EXPECT_THROW(makeRenderer("no-such-scene", RendererOptions{}), InputError);
  EXPECT_THROW(makeRenderer(Gyroid{4.0f, 2.0f, 0.3f, 0.0f}, RendererOptions{}), InputError);
  std::unique_ptr<Renderer> r = makeRenderer(GYROID, RendererOptions{});
  EXPECT_EQ(r->options().scheduler.poolBricks, DEFAULT_POOL_BRICKS_CPU) << "resolved default";
  EXPECT_THROW(r->render(poseAt(0), static_cast<uint32_t*>(nullptr), nullptr), InputError);
}

TEST(UserProducer, GpuSchedulersRenderTheSameGyroid) {
  GVDP_REQUIRE_GPU();
  Frames sp = renderFrames(GYROID, Backend::Cuda, SchedulerKind::Sp, 4);
  expectSameFrames(sp, renderFrames(GYROID, Backend::Cuda, SchedulerKind::Pt, 4), "pt");
  expectSameFrames(sp, renderFrames(GYROID, Backend::Cuda, SchedulerKind::Graph, 4), "graph");
#if GVDP_CDP
  // This translation unit is relocatable device code, device-linked with the library's.
  expectSameFrames(sp, renderFrames(GYROID, Backend::Cuda, SchedulerKind::Dp, 4), "dp");
#else
  // A build without CUDA Dynamic Parallelism: dp says so instead of rendering.
  RendererOptions o;
  o.scheduler = {Backend::Cuda, SchedulerKind::Dp};
  EXPECT_THROW(makeRenderer(GYROID, o), InputError);
#endif
  Frames cpu = renderFrames(GYROID, Backend::Cpu, SchedulerKind::Sp, 4);
  for (size_t f = 0; f < sp.images.size(); ++f) {
    double db = psnr(sp.images[f], cpu.images[f]);
    std::printf("[ measure ] gyroid frame %zu sp cuda vs cpu (96x64): PSNR %.2f dB\n", f, db);
    EXPECT_GE(db, 40.0) << "frame " << f;
  }
}

#if GVDP_HAS_CUDA && defined(__CUDACC__)
// Holds a stream for about `ns` nanoseconds.
__global__ void busyKernel(uint64_t ns) {
  uint64_t start = clockNanoseconds();
  while (clockNanoseconds() - start < ns) __nanosleep(1000);
}
#endif

// Frames rendered to device memory on the caller's stream equal the host images (every CUDA
// scheduler this translation unit has), also when the caller's stream is busy: frame f + 1 may
// not overwrite the renderer's image before frame f's copy has run.
TEST(UserProducer, GpuFramesToDeviceMemoryOnAStreamEqualHostFrames) {
  GVDP_REQUIRE_GPU();
#if GVDP_HAS_CUDA && defined(__CUDACC__)
  constexpr int FRAMES = 3;
  for (SchedulerKind kind : {SchedulerKind::Direct, SchedulerKind::Sp, SchedulerKind::Pt,
                             SchedulerKind::Graph, SchedulerKind::Dp}) {
    if (kind == SchedulerKind::Dp && !GVDP_CDP) continue;
    Frames host = renderFrames(GYROID, Backend::Cuda, kind, FRAMES);
    RendererOptions o;
    o.scheduler = {Backend::Cuda, kind};
    o.width = 96;
    o.height = 64;
    std::unique_ptr<Renderer> r = makeRenderer(GYROID, o);
    size_t pixels = static_cast<size_t>(o.width) * o.height;
    uint32_t* device = nullptr;
    cudaStream_t stream = nullptr;
    ASSERT_EQ(cudaMalloc(&device, FRAMES * pixels * sizeof(uint32_t)), cudaSuccess);
    ASSERT_EQ(cudaStreamCreateWithFlags(&stream, cudaStreamNonBlocking), cudaSuccess);
    busyKernel<<<1, 1, 0, stream>>>(50'000'000);  // the first copies wait 50 ms
    for (int f = 0; f < FRAMES; ++f) {
      FrameStats stats = r->render(poseAt(f), device + f * pixels, stream);
      EXPECT_EQ(stats.unfinishedPixels, 0);
    }
    std::vector<uint32_t> back(FRAMES * pixels);
    ASSERT_EQ(cudaMemcpyAsync(back.data(), device, back.size() * sizeof(uint32_t),
                              cudaMemcpyDeviceToHost, stream),
              cudaSuccess);
    ASSERT_EQ(cudaStreamSynchronize(stream), cudaSuccess);
    for (int f = 0; f < FRAMES; ++f)
      EXPECT_TRUE(std::equal(host.images[f].pixels.begin(), host.images[f].pixels.end(),
                             back.begin() + f * pixels))
          << schedulerName(kind) << " frame " << f;
    cudaStreamDestroy(stream);
    cudaFree(device);
  }
#else
  GTEST_SKIP() << "this test's translation unit was not compiled by nvcc";
#endif
}

}  // namespace gvdp::detail
