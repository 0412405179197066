// The quadtree subdivision on the GPU (seed paper, "GPU quadtree subdivision for out-of-core
// rendering"): the sum-mipmap build and three ways to run the top-down rule (decideNode):
//   MultiPass  the seed's baseline: a pass per level, a thread per active node, the host reading
//              the counts back after each pass to size the next launch;
//   Subtree    the seed's optimisation: L levels per pass, a thread per node L levels under each
//              active node, descending from the top; one writer per tile (the emitted node's
//              top-left descendant) and one per next-pass node (itself), so no duplicates;
//   Dynamic    CUDA Dynamic Parallelism (CDP2): a 4-thread grid per subdivided node, launched from
//              the device; the host waits once. Needs relocatable device code and GVDP_CDP.
// Tiles are appended with an atomic counter; their order is the device's (sortCanonical).
#include <cuda_runtime.h>

#include <algorithm>
#include <array>

#include "gvdp/base/cuda_util.h"
#include "gvdp/tiles/quadtree.h"

#if GVDP_CDP && defined(__CUDACC_RDC__)
#define GVDP_QUADTREE_CDP 1
#else
#define GVDP_QUADTREE_CDP 0
#endif

namespace gvdp::detail {
namespace {

constexpr int BLOCK = 256;
// The mipmap's top levels (depths TOP_DEPTH..0, at most 4^TOP_DEPTH nodes each): one block, one
// launch.
constexpr int TOP_DEPTH = 5;
constexpr int TOP_BLOCK = 1 << (2 * TOP_DEPTH);
// Device counters, read back by the host in one copy after each pass. ACTIVE + d counts the
// active nodes of depth d, so no counter needs a reset between passes.
enum Counter { TILES, LAUNCHES, LAUNCH_FAILURES, ACTIVE, COUNTER_COUNT = ACTIVE + 16 };
static_assert(QUADTREE_MAX_LEVELS + 2 <= COUNTER_COUNT - ACTIVE);

// Active nodes as x | y << 16 (x, y < 2^13).
__device__ __forceinline__ uint32_t packNode(int x, int y) {
  return static_cast<uint32_t>(x) | static_cast<uint32_t>(y) << 16;
}

__device__ __forceinline__ void emitTile(Tile* tiles, uint32_t* counters, int depth, int x, int y,
                                         const NodeDecision& n) {
  tiles[atomicAdd(&counters[TILES], 1u)] = Tile{depth, x, y, n.sum, n.overflows};
}

unsigned blocksFor(uint64_t threads, int block = BLOCK) {
  return static_cast<unsigned>((threads + block - 1) / block);
}

// --- Sum-mipmap -------------------------------------------------------------------------------

// Depth K (the zero-padded importance, widened) and depth K - 1 in one pass: a thread per node of
// depth K - 1 reads its four blocks. K == 0: the single block.
__global__ void mipmapFinestKernel(const uint32_t* importance, int width, int height, int levels,
                                   uint64_t* sums) {
  int depth = levels > 0 ? levels - 1 : 0;
  int side = 1 << depth;
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= uint32_t(side) * side) return;
  int x = static_cast<int>(i % side), y = static_cast<int>(i / side);
  if (levels == 0) {
    sums[0] = importance[0];
    return;
  }
  uint64_t* finest = sums + mipmapDepthOffset(levels);
  uint64_t total = 0;
  for (int c = 0; c < 4; ++c) {
    int bx = 2 * x + (c & 1), by = 2 * y + (c >> 1);
    uint64_t v = bx < width && by < height ? importance[int64_t{by} * width + bx] : 0;
    finest[(int64_t{by} << levels) + bx] = v;
    total += v;
  }
  sums[mipmapDepthOffset(depth) + i] = total;
}

__device__ __forceinline__ uint64_t childSum(const uint64_t* sums, int depth, int x, int y) {
  const uint64_t* c = sums + mipmapDepthOffset(depth + 1) + (int64_t{2 * y} << (depth + 1)) + 2 * x;
  int64_t row = int64_t{1} << (depth + 1);
  return c[0] + c[1] + c[row] + c[row + 1];
}

__global__ void mipmapLevelKernel(uint64_t* sums, int depth) {
  int side = 1 << depth;
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= uint32_t(side) * side) return;
  sums[mipmapDepthOffset(depth) + i] =
      childSum(sums, depth, static_cast<int>(i % side), static_cast<int>(i / side));
}

// Depths `from`..0 (from <= TOP_DEPTH) by one block: a launch each would cost more than the work.
// __syncthreads makes the block's global writes of one level visible to the next.
__global__ void __launch_bounds__(TOP_BLOCK) mipmapTopKernel(uint64_t* sums, int from) {
  for (int depth = from; depth >= 0; --depth) {
    int side = 1 << depth;
    int i = static_cast<int>(threadIdx.x);
    if (i < side * side)
      sums[mipmapDepthOffset(depth) + i] = childSum(sums, depth, i % side, i / side);
    __syncthreads();
  }
}

// --- MultiPass ----------------------------------------------------------------------------------

__global__ void multiPassKernel(QuadtreeView q, int depth, const uint32_t* active, uint32_t count,
                                uint32_t* nextActive, Tile* tiles, uint32_t* counters) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= count) return;
  int x = static_cast<int>(active[i] & 0xffffu), y = static_cast<int>(active[i] >> 16);
  NodeDecision n = decideNode(q, depth, x, y);
  if (n.action == NodeAction::Emit) emitTile(tiles, counters, depth, x, y, n);
  if (n.action != NodeAction::Subdivide) return;
  // Only valid children are pushed: the next pass's count is the nodes it has to decide.
  uint32_t children[4];
  uint32_t valid = 0;
  for (int c = 0; c < 4; ++c) {
    int cx = 2 * x + (c & 1), cy = 2 * y + (c >> 1);
    if (nodeIsValid(q, depth + 1, cx, cy)) children[valid++] = packNode(cx, cy);
  }
  uint32_t at = atomicAdd(&counters[ACTIVE + depth + 1], valid);
  for (uint32_t c = 0; c < valid; ++c) nextActive[at + c] = children[c];
}

// --- Subtree ------------------------------------------------------------------------------------

// A thread per node `levels` below an active node of `depth` (row-major in the subtree, so a
// warp shares its ancestors' reads). It decides its ancestors top-down: at the first emitted one
// it writes the tile if it is that node's top-left descendant, and stops. A thread that reaches
// its own node still subdividing makes it active for the next pass; in the last pass (`decideLast`:
// its node is at depth K) it decides it as well.
__global__ void subtreeKernel(QuadtreeView q, int depth, int levels, bool decideLast,
                              const uint32_t* active, uint32_t count, uint32_t* nextActive,
                              Tile* tiles, uint32_t* counters) {
  uint64_t t = blockIdx.x * uint64_t{blockDim.x} + threadIdx.x;
  if (t >= uint64_t{count} << (2 * levels)) return;
  uint32_t top = active[t >> (2 * levels)];
  uint32_t local = static_cast<uint32_t>(t) & ((1u << (2 * levels)) - 1);
  int mask = (1 << levels) - 1;
  int fx = (static_cast<int>(top & 0xffffu) << levels) | (static_cast<int>(local) & mask);
  int fy = (static_cast<int>(top >> 16) << levels) | static_cast<int>(local >> levels);
  int finest = depth + levels;
  // Outside the grid: every ancestor this thread could write has a valid top-left block, which is
  // another thread's.
  if (!nodeIsValid(q, finest, fx, fy)) return;
  int last = decideLast ? finest : finest - 1;
  for (int d = depth; d <= last; ++d) {
    int shift = finest - d;
    int x = fx >> shift, y = fy >> shift;
    NodeDecision n = decideNode(q, d, x, y);
    if (n.action == NodeAction::Subdivide) continue;
    bool firstDescendant = ((fx | fy) & ((1 << shift) - 1)) == 0;
    if (n.action == NodeAction::Emit && firstDescendant) emitTile(tiles, counters, d, x, y, n);
    return;
  }
  if (!decideLast) nextActive[atomicAdd(&counters[ACTIVE + finest], 1u)] = packNode(fx, fy);
}

// --- Dynamic ------------------------------------------------------------------------------------

#if GVDP_QUADTREE_CDP
// A thread per child of the node (depth - 1, x0 / 2, y0 / 2); launched with one thread for the
// root. The view comes by pointer, so that the many device launches stay small.
__global__ void dynamicKernel(const QuadtreeView* view, int depth, int x0, int y0, Tile* tiles,
                              uint32_t* counters) {
  const QuadtreeView& q = *view;
  int x = x0 + static_cast<int>(threadIdx.x & 1), y = y0 + static_cast<int>(threadIdx.x >> 1);
  NodeDecision n = decideNode(q, depth, x, y);
  if (n.action == NodeAction::Emit) emitTile(tiles, counters, depth, x, y, n);
  if (n.action != NodeAction::Subdivide) return;
  dynamicKernel<<<1, 4, 0, cudaStreamFireAndForget>>>(view, depth + 1, 2 * x, 2 * y, tiles,
                                                      counters);
  // A refused launch loses a subtree's tiles: counted, and the host throws.
  if (cudaGetLastError() == cudaSuccess)
    atomicAdd(&counters[LAUNCHES], 1u);
  else
    atomicAdd(&counters[LAUNCH_FAILURES], 1u);
}

// Dynamic raises CDP's pending-launch buffer to the launches it may make, at most this many (the
// buffer is device memory reserved for good); beyond, a refused launch is an error, not a loss.
constexpr size_t MAX_PENDING_LAUNCHES = size_t{1} << 20;

// Upper bound of Dynamic's device launches: the valid nodes above depth K (one each if all
// subdivide).
size_t launchBound(int width, int height, int levels) {
  size_t n = 0;
  for (int d = 0; d < levels; ++d) {
    int shift = levels - d;
    n += size_t((width + (1 << shift) - 1) >> shift) * size_t((height + (1 << shift) - 1) >> shift);
  }
  return n;
}

#endif

}  // namespace

struct GpuQuadtree::Impl {
  int width = 0, height = 0, levels = 0;
  bool hasImportance = false, hasMipmap = false;
  DeviceBuffer<uint32_t> importance;
  DeviceBuffer<uint64_t> sums;
  // At most one tile or active node per valid block: tiles (and a depth's nodes) are disjoint.
  DeviceBuffer<Tile> tiles;
  std::array<DeviceBuffer<uint32_t>, 2> active;
  DeviceBuffer<uint32_t> counters{COUNTER_COUNT};
  DeviceBuffer<QuadtreeView> view{1};  // Dynamic's, read by every device launch
  uint32_t* hostCounters = nullptr;    // page-locked: the per-pass read back is a short copy
  uint64_t tileCount = 0;

  Impl() { GVDP_CUDA_CHECK(cudaMallocHost(&hostCounters, COUNTER_COUNT * sizeof(uint32_t))); }
  ~Impl() { cudaFreeHost(hostCounters); }

  void resize(int w, int h) {
    int k = quadtreeLevels(w, h);
    size_t blocks = size_t(w) * size_t(h);
    if (sums.size() != mipmapSize(k)) sums = DeviceBuffer<uint64_t>(mipmapSize(k));
    if (tiles.size() != blocks) {
      tiles = DeviceBuffer<Tile>(blocks);
      for (auto& a : active) a = DeviceBuffer<uint32_t>(blocks);
    }
    width = w;
    height = h;
    levels = k;
    hasImportance = hasMipmap = false;
    tileCount = 0;
  }

  void readCounters(cudaStream_t stream) {
    readDevice(hostCounters, counters.data(), counters.bytes(), stream);
  }

  void runMultiPass(const QuadtreeView& q, cudaStream_t stream, SubdivisionStats& s);
  void runSubtree(const QuadtreeView& q, int levelsPerPass, cudaStream_t stream,
                  SubdivisionStats& s);
  void runDynamic(const QuadtreeView& q, cudaStream_t stream, SubdivisionStats& s);
};

void GpuQuadtree::Impl::runMultiPass(const QuadtreeView& q, cudaStream_t stream,
                                     SubdivisionStats& s) {
  uint32_t count = 1;  // the root, packed as 0
  fillDevice(active[0].data(), 0, sizeof(uint32_t), stream);
  for (int depth = 0, cur = 0; count > 0; ++depth, cur ^= 1) {
    ++s.passes;
    s.activeNodes.push_back(count);
    multiPassKernel<<<blocksFor(count), BLOCK, 0, stream>>>(
        q, depth, active[cur].data(), count, active[cur ^ 1].data(), tiles.data(), counters.data());
    GVDP_CUDA_CHECK(cudaGetLastError());
    readCounters(stream);  // the seed's baseline: the host sizes every pass
    count = hostCounters[ACTIVE + depth + 1];
  }
}

void GpuQuadtree::Impl::runSubtree(const QuadtreeView& q, int levelsPerPass, cudaStream_t stream,
                                   SubdivisionStats& s) {
  uint32_t count = 1;
  fillDevice(active[0].data(), 0, sizeof(uint32_t), stream);
  for (int depth = 0, cur = 0; count > 0; depth += levelsPerPass, cur ^= 1) {
    ++s.passes;
    s.activeNodes.push_back(count);
    // A pass that reaches depth K decides it too: single blocks never subdivide.
    bool last = depth + levelsPerPass >= levels;
    int passLevels = last ? levels - depth : levelsPerPass;
    subtreeKernel<<<blocksFor(uint64_t{count} << (2 * passLevels)), BLOCK, 0, stream>>>(
        q, depth, passLevels, last, active[cur].data(), count, active[cur ^ 1].data(), tiles.data(),
        counters.data());
    GVDP_CUDA_CHECK(cudaGetLastError());
    readCounters(stream);
    count = last ? 0 : hostCounters[ACTIVE + depth + levelsPerPass];
  }
}

void GpuQuadtree::Impl::runDynamic([[maybe_unused]] const QuadtreeView& q,
                                   [[maybe_unused]] cudaStream_t stream,
                                   [[maybe_unused]] SubdivisionStats& s) {
#if GVDP_QUADTREE_CDP
  // Every launch may be pending at once (fire-and-forget grids run in any order): raise the
  // buffer to the bound, never lower it (dp shares it).
  size_t want = std::min(launchBound(width, height, levels), MAX_PENDING_LAUNCHES), have = 0;
  GVDP_CUDA_CHECK(cudaDeviceGetLimit(&have, cudaLimitDevRuntimePendingLaunchCount));
  if (have < want) GVDP_CUDA_CHECK(cudaDeviceSetLimit(cudaLimitDevRuntimePendingLaunchCount, want));
  writeDevice(view.data(), &q, sizeof q, stream);
  dynamicKernel<<<1, 1, 0, stream>>>(view.data(), 0, 0, 0, tiles.data(), counters.data());
  GVDP_CUDA_CHECK(cudaGetLastError());
  readCounters(stream);  // a grid completes with all the grids it launched
  s.passes = 1;
  s.activeNodes = {1};
  s.deviceLaunches = hostCounters[LAUNCHES];
  GVDP_CHECK(hostCounters[LAUNCH_FAILURES] == 0, hostCounters[LAUNCH_FAILURES],
             " device launches refused (CDP pending-launch limit ", std::max(have, want),
             "): tiles lost");
#else
  throw InputError(
      "quadtree method 'dynamic' unavailable: built without CUDA Dynamic Parallelism "
      "(GVDP_CDP=ON and relocatable device code)");
#endif
}

GpuQuadtree::GpuQuadtree() = default;
GpuQuadtree::~GpuQuadtree() = default;

void GpuQuadtree::upload(const uint32_t* importance, int width, int height, GpuStream stream) {
  if (!impl_) impl_ = std::make_unique<Impl>();
  impl_->resize(width, height);
  size_t n = size_t(width) * size_t(height);
  if (impl_->importance.size() != n) impl_->importance = DeviceBuffer<uint32_t>(n);
  writeDevice(impl_->importance.data(), importance, n * sizeof(uint32_t), stream);
  impl_->hasImportance = true;
}

void GpuQuadtree::buildMipmap(GpuStream stream) {
  GVDP_INPUT_CHECK(impl_ && impl_->hasImportance, "quadtree: buildMipmap() before upload()");
  Impl& m = *impl_;
  int k = m.levels;
  int finestParents = k > 0 ? 1 << (2 * (k - 1)) : 1;
  mipmapFinestKernel<<<blocksFor(finestParents), BLOCK, 0, stream>>>(m.importance.data(), m.width,
                                                                     m.height, k, m.sums.data());
  GVDP_CUDA_CHECK(cudaGetLastError());
  for (int d = k - 2; d > TOP_DEPTH; --d) {
    mipmapLevelKernel<<<blocksFor(uint64_t{1} << (2 * d)), BLOCK, 0, stream>>>(m.sums.data(), d);
    GVDP_CUDA_CHECK(cudaGetLastError());
  }
  if (k >= 2) {
    mipmapTopKernel<<<1, TOP_BLOCK, 0, stream>>>(m.sums.data(), std::min(k - 2, TOP_DEPTH));
    GVDP_CUDA_CHECK(cudaGetLastError());
  }
  m.hasMipmap = true;
}

void GpuQuadtree::uploadMipmap(const SumMipmap& mipmap, GpuStream stream) {
  GVDP_INPUT_CHECK(mipmap.values.size() == mipmapSize(mipmap.levels), "sum-mipmap not built");
  if (!impl_) impl_ = std::make_unique<Impl>();
  impl_->resize(mipmap.width, mipmap.height);
  writeDevice(impl_->sums.data(), mipmap.values.data(), impl_->sums.bytes(), stream);
  impl_->hasMipmap = true;
}

SumMipmap GpuQuadtree::downloadMipmap(GpuStream stream) const {
  GVDP_INPUT_CHECK(impl_ && impl_->hasMipmap, "quadtree: no sum-mipmap on the device");
  SumMipmap m;
  m.width = impl_->width;
  m.height = impl_->height;
  m.levels = impl_->levels;
  m.values.resize(impl_->sums.size());
  readDevice(m.values.data(), impl_->sums.data(), impl_->sums.bytes(), stream);
  return m;
}

uint64_t GpuQuadtree::run(const SubdivisionParams& p, SubdivisionMethod method, int levelsPerPass,
                          GpuStream stream, SubdivisionStats* stats) {
  GVDP_INPUT_CHECK(impl_ && impl_->hasMipmap, "quadtree: run() before the sum-mipmap is built");
  Impl& m = *impl_;
  checkSubdivisionParams(m.width, m.height, p);
  GVDP_INPUT_CHECK(method != SubdivisionMethod::Subtree ||
                       (levelsPerPass >= 1 && levelsPerPass <= QUADTREE_MAX_LEVELS_PER_PASS),
                   "levels per pass ", levelsPerPass, ": out of range 1..",
                   QUADTREE_MAX_LEVELS_PER_PASS);
  QuadtreeView q{m.sums.data(), m.levels, m.width, m.height, p};
  NvtxRange range(methodName(method));
  SubdivisionStats s;
  m.tileCount = 0;
  fillDevice(m.counters.data(), 0, m.counters.bytes(), stream);
  switch (method) {
    case SubdivisionMethod::MultiPass:
      m.runMultiPass(q, stream, s);
      break;
    case SubdivisionMethod::Subtree:
      m.runSubtree(q, levelsPerPass, stream, s);
      break;
    case SubdivisionMethod::Dynamic:
      m.runDynamic(q, stream, s);
      break;
    case SubdivisionMethod::Cpu:
      throw InputError("quadtree method 'cpu' does not run on the GPU: use subdivide()");
  }
  m.tileCount = m.hostCounters[TILES];
  if (stats) *stats = std::move(s);
  return m.tileCount;
}

std::vector<Tile> GpuQuadtree::tiles(GpuStream stream) const {
  GVDP_INPUT_CHECK(impl_, "quadtree: tiles() before run()");
  std::vector<Tile> out(impl_->tileCount);
  if (!out.empty()) readDevice(out.data(), impl_->tiles.data(), out.size() * sizeof(Tile), stream);
  return out;
}

}  // namespace gvdp::detail
