// Seed 004's level-by-level kd-tree builder on the GPU (kdtree_build.h buildKdTreeCuda): the
// steps of kdtree_parallel.cpp, one CUB call or one element-wise kernel each, over the same flat
// arrays (a level's nodes, its slots, its events per axis), the rules being kdtree.h's GVDP_HD
// functions. Nodes and leaf triangles are written in the same places as the parallel builder's,
// so the two trees are equal even in storage. On the device: the triangles' boxes (from the
// uploaded vertices and indices), the root box (cub::DeviceReduce), the root events (counted,
// cub::DeviceScan, written in triangle order, then a stable cub::DeviceRadixSort on eventKey:
// kdEventLess's order) and every level. The host only reads back each level's totals (to size
// the next arrays: two small reads a level) and its nodes and leaf triangles. A node's best split
// is a reduction by key over the events' owners (cub::DeviceReduce::ReduceByKey, the candidates
// evaluated as CUB reads them), not one segment per node; the arrays come from a memory pool of
// the build's own, grown in stream order. Built with --fmad=false (src/CMakeLists.txt) on top of
// the explicitly rounded operations of base/rounded_math.h.
#include <cuda_runtime.h>

#include <thrust/iterator/counting_iterator.h>
#include <thrust/iterator/transform_iterator.h>
#include <algorithm>
#include <array>
#include <cstdint>
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_reduce.cuh>
#include <cub/device/device_scan.cuh>
#include <utility>

#include "gvdp/base/cuda_util.h"
#include "gvdp/base/gpu.h"
#include "gvdp/mesh/kdtree_build.h"

namespace gvdp::detail {
namespace {

constexpr int BLOCK = 256;

// --- kernels (one thread per element; i < n) ------------------------------------------------

__global__ void triangleBoxesKernel(const Vec3f* vertices, const uint32_t* indices, uint32_t n,
                                    Box3f* boxes) {
  uint32_t t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= n) return;
  boxes[t] = kdTriangleBox(vertices[indices[3 * t]], vertices[indices[3 * t + 1]],
                           vertices[indices[3 * t + 2]]);
}

// 1 event for a triangle flat on `axis`, else 2; count[n] = 0 (the scan's total lands there).
__global__ void rootEventCountKernel(const Box3f* boxes, uint32_t n, int axis, uint32_t* count) {
  uint32_t t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t > n) return;
  count[t] = t == n ? 0u : (component(boxes[t].lo, axis) == component(boxes[t].hi, axis) ? 1u : 2u);
}

// The events of kdRootEvents in triangle order, their sort keys, and their indices.
__global__ void rootEventsKernel(const Box3f* boxes, uint32_t n, int axis, const uint32_t* offset,
                                 KdEvent* ev, uint64_t* key, uint32_t* index) {
  uint32_t t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= n) return;
  float lo = component(boxes[t].lo, axis), hi = component(boxes[t].hi, axis);
  uint32_t o = offset[t];
  KdEvent e[2];
  int count = 1;
  if (lo == hi) {
    e[0] = kdEvent(lo, t, KD_EVENT_PLANAR);
  } else {
    e[0] = kdEvent(lo, t, KD_EVENT_START);
    e[1] = kdEvent(hi, t, KD_EVENT_END);
    count = 2;
  }
  for (int k = 0; k < count; ++k) {
    ev[o + k] = e[k];
    key[o + k] = eventKey(e[k]);
    index[o + k] = o + k;
  }
}

__global__ void gatherEventsKernel(const KdEvent* in, const uint32_t* index, uint32_t n,
                                   KdEvent* out) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) out[i] = in[index[i]];
}

__global__ void iotaKernel(uint32_t* a, uint32_t n) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) a[i] = i;
}

// (1) an event's counts (the scan's input) and its candidate (evaluateEvent, with its node's
// counts before it: the reduction's input), computed where CUB reads them (no arrays between).
struct CountsOf {
  __host__ __device__ KdEventCounts operator()(const KdEvent& e) const { return countsOf(e); }
};
struct EvaluateEvent {
  const KdEvent* ev;
  const uint32_t* evOwner;
  const uint32_t* evBegin;
  const KdEventCounts* before;
  const uint32_t* triBegin;
  const Box3f* box;
  int axis;
  __host__ __device__ KdSplit operator()(uint32_t i) const {
    uint32_t j = evOwner[i], b = evBegin[j];
    return evaluateEvent(ev, i, b, evBegin[j + 1], before[i] - before[b],
                         triBegin[j + 1] - triBegin[j], box[j], axis);
  }
};

__global__ void noSplitKernel(uint32_t m, KdSplit* best) {
  uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j < m) best[j] = noSplit();
}

// The best of every run of one owner (cub::DeviceReduce::ReduceByKey over the events' owners:
// one run per node with events on this axis) merged into its node's best; a node without events
// keeps noSplit(), as a reduction of its empty segment starting from noSplit() would give.
__global__ void mergeRunsKernel(const uint32_t* runOwner, const KdSplit* runBest,
                                const uint32_t* runs, uint32_t maxRuns, KdSplit* best) {
  uint32_t k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= maxRuns || k >= *runs) return;
  uint32_t j = runOwner[k];
  if (betterSplit(runBest[k], best[j])) best[j] = runBest[k];
}

// Up to four device values into `out` (one read-back for a level's totals).
__global__ void totalsKernel(const uint32_t* a, const uint32_t* b, const uint32_t* c,
                             const uint32_t* d, uint32_t* out) {
  if (threadIdx.x == 0) {
    out[0] = *a;
    out[1] = b ? *b : 0u;
    out[2] = c ? *c : 0u;
    out[3] = d ? *d : 0u;
  }
}

// (2) the leaf rule; split[m] = leafTris[m] = 0 (the scans' totals land there).
// Two counts are scanned at once as one uint64_t (low: the first, high: the second; neither
// total reaches 2^31, so no carry crosses). split and flags[m] = 0 (the scan's total lands there).
__global__ void decideKernel(const Box3f* box, const uint32_t* triBegin, const KdSplit* best,
                             uint32_t m, int depth, uint32_t* split, uint64_t* flags) {
  uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j > m) return;
  if (j == m) {
    split[m] = 0;
    flags[m] = 0;
    return;
  }
  uint32_t n = triBegin[j + 1] - triBegin[j];
  bool s = shouldSplit(box[j], n, depth, best[j]);
  split[j] = s;
  flags[j] = s ? 1u : uint64_t{n} << 32;
}

// The ranks among the split nodes and the leaf triangle offsets, out of decideKernel's scan.
__global__ void unpackKernel(const uint64_t* scan, uint32_t n, uint32_t* lo, uint32_t* hi) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i > n) return;
  lo[i] = static_cast<uint32_t>(scan[i]);
  hi[i] = static_cast<uint32_t>(scan[i] >> 32);
}

__device__ __forceinline__ uint32_t scanL(const uint64_t* scan, uint32_t i) {
  return static_cast<uint32_t>(scan[i]);
}
__device__ __forceinline__ uint32_t scanR(const uint64_t* scan, uint32_t i) {
  return static_cast<uint32_t>(scan[i] >> 32);
}

// (3) the sides of every slot of a split node, from its split axis's events (one writer each).
__global__ void sidesKernel(const KdEvent* ev, uint32_t n, const uint32_t* evOwner,
                            const uint32_t* split, const KdSplit* best, int axis, uint8_t* left,
                            uint8_t* right) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  uint32_t j = evOwner[i];
  if (!split[j] || best[j].axis != axis) return;
  KdEvent e = ev[i];
  uint32_t sides = eventSides(e, best[j].pos), slot = eventTriangle(e), type = eventType(e);
  if (type != KD_EVENT_END) left[slot] = (sides & KD_LEFT) != 0;
  if (type != KD_EVENT_START) right[slot] = (sides & KD_RIGHT) != 0;
}

// (4) the level's nodes (children: the next level's nodes nextBase + 2 rank, +1) ...
__global__ void nodesKernel(const uint32_t* split, const KdSplit* best, const uint32_t* rank,
                            const uint32_t* leafOffset, const uint32_t* triBegin, uint32_t m,
                            uint32_t nextBase, uint32_t leafBase, KdNode* nodes) {
  uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j >= m) return;
  nodes[j] = split[j] ? kdInterior(best[j].axis, best[j].pos, nextBase + 2 * rank[j])
                      : kdLeaf(leafBase + leafOffset[j], triBegin[j + 1] - triBegin[j]);
}

// ... and its leaves' triangles. A node's slots hold ascending triangle ids (the root's are
// 0..n-1 and every compaction keeps their order), so a leaf's list needs no sort.
__global__ void leafTrianglesKernel(const uint32_t* tri, const uint32_t* triOwner, uint32_t slots,
                                    const uint32_t* split, const uint32_t* triBegin,
                                    const uint32_t* leafOffset, uint32_t* out) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= slots) return;
  uint32_t j = triOwner[i];
  if (!split[j]) out[leafOffset[j] + i - triBegin[j]] = tri[i];
}

// (5) the next level: children's boxes ...
__global__ void childBoxesKernel(const Box3f* box, const uint32_t* split, const KdSplit* best,
                                 const uint32_t* rank, uint32_t m, Box3f* next) {
  uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j >= m || !split[j]) return;
  next[2 * rank[j]] = leftBox(box[j], best[j].axis, best[j].pos);
  next[2 * rank[j] + 1] = rightBox(box[j], best[j].axis, best[j].pos);
}

// ... the flags "this element goes to the left / right child" of slots (slotOf: null) or events
// (slotOf: the events, whose triangle field is their slot), packed (left low, right high) for one
// scan; goes[n] = 0 ...
__global__ void goesKernel(const KdEvent* slotOf, uint32_t n, const uint32_t* triOwner,
                           const uint32_t* split, const uint8_t* left, const uint8_t* right,
                           uint64_t* goes) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i > n) return;
  if (i == n) {
    goes[n] = 0;
    return;
  }
  uint32_t slot = slotOf ? eventTriangle(slotOf[i]) : i;
  bool s = split[triOwner[slot]] != 0;
  goes[i] = uint64_t{s && left[slot]} | uint64_t{s && right[slot]} << 32;
}

// ... the children's element counts in child order (from the scans of those flags) ...
__global__ void childCountsKernel(const uint32_t* split, const uint32_t* rank,
                                  const uint32_t* begin, const uint64_t* scan, uint32_t m,
                                  uint32_t* childCount) {
  uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j >= m || !split[j]) return;
  childCount[2 * rank[j]] = scanL(scan, begin[j + 1]) - scanL(scan, begin[j]);
  childCount[2 * rank[j] + 1] = scanR(scan, begin[j + 1]) - scanR(scan, begin[j]);
}

// ... the slots placed in their children's segments, order kept ...
__global__ void scatterSlotsKernel(const uint32_t* tri, const uint32_t* triOwner, uint32_t slots,
                                   const uint32_t* split, const uint32_t* rank,
                                   const uint32_t* triBegin, const uint8_t* left,
                                   const uint8_t* right, const uint64_t* scan,
                                   const uint32_t* nextBegin, uint32_t* nextTri,
                                   uint32_t* nextOwner, uint32_t* slotL, uint32_t* slotR) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= slots) return;
  uint32_t j = triOwner[i];
  if (!split[j]) return;
  uint32_t b = triBegin[j], c = 2 * rank[j];
  if (left[i]) {
    uint32_t dst = nextBegin[c] + scanL(scan, i) - scanL(scan, b);
    nextTri[dst] = tri[i];
    nextOwner[dst] = c;
    slotL[i] = dst;
  }
  if (right[i]) {
    uint32_t dst = nextBegin[c + 1] + scanR(scan, i) - scanR(scan, b);
    nextTri[dst] = tri[i];
    nextOwner[dst] = c + 1;
    slotR[i] = dst;
  }
}

// ... and the events likewise, renamed to their slots in the children.
__global__ void scatterEventsKernel(const KdEvent* ev, uint32_t n, const uint32_t* evOwner,
                                    const uint32_t* split, const uint32_t* rank,
                                    const uint32_t* evBegin, const uint8_t* left,
                                    const uint8_t* right, const uint64_t* scan,
                                    const uint32_t* nextBegin, const uint32_t* slotL,
                                    const uint32_t* slotR, KdEvent* nextEv, uint32_t* nextOwner) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  uint32_t j = evOwner[i];
  if (!split[j]) return;
  KdEvent e = ev[i];
  uint32_t slot = eventTriangle(e), c = 2 * rank[j];
  if (left[slot]) {
    uint32_t dst = nextBegin[c] + scanL(scan, i) - scanL(scan, evBegin[j]);
    nextEv[dst] = {e.pos, slotL[slot] << 2 | eventType(e)};
    nextOwner[dst] = c;
  }
  if (right[slot]) {
    uint32_t dst = nextBegin[c + 1] + scanR(scan, i) - scanR(scan, evBegin[j]);
    nextEv[dst] = {e.pos, slotR[slot] << 2 | eventType(e)};
    nextOwner[dst] = c + 1;
  }
}

// --- CUB operators -------------------------------------------------------------------------------

struct AddCounts {
  __device__ KdEventCounts operator()(KdEventCounts a, KdEventCounts b) const { return a + b; }
};
// The better of two splits (betterSplit is a total order on one node's candidates).
struct BestOf {
  __device__ KdSplit operator()(const KdSplit& a, const KdSplit& b) const {
    return betterSplit(b, a) ? b : a;
  }
};
struct MergeBoxes {
  __device__ Box3f operator()(const Box3f& a, const Box3f& b) const { return merge(a, b); }
};

// --- host side -----------------------------------------------------------------------------------

// At least one block: every kernel checks its index against its count.
unsigned blocks(uint64_t n) {
  return n == 0 ? 1u : static_cast<unsigned>((n + BLOCK - 1) / BLOCK);
}
void checkLaunch() {
  GVDP_CUDA_CHECK(cudaGetLastError());
}

// The build's device memory: a memory pool of its own, allocated from and freed to in stream
// order on the build's stream, that keeps what is freed (release threshold: never) for the
// build's later allocations: growing an array costs no device synchronisation, and after the
// first levels no cudaMalloc. Destroyed (its memory released) when the build returns.
struct Pool {
  cudaStream_t stream = nullptr;
  cudaMemPool_t pool = nullptr;

  explicit Pool(cudaStream_t s) : stream(s) {
    int device = 0;
    GVDP_CUDA_CHECK(cudaGetDevice(&device));
    cudaMemPoolProps props{};
    props.allocType = cudaMemAllocationTypePinned;
    props.location.type = cudaMemLocationTypeDevice;
    props.location.id = device;
    GVDP_CUDA_CHECK(cudaMemPoolCreate(&pool, &props));
    uint64_t never = UINT64_MAX;
    GVDP_CUDA_CHECK(cudaMemPoolSetAttribute(pool, cudaMemPoolAttrReleaseThreshold, &never));
  }
  ~Pool() {
    cudaStreamSynchronize(stream);
    cudaMemPoolDestroy(pool);  // its arrays, freed before, return to it in stream order
  }
  Pool(const Pool&) = delete;
  Pool& operator=(const Pool&) = delete;
};

// A device array of the pool (freed to it, in stream order, when destroyed or grown).
template <class T>
class PoolArray {
 public:
  PoolArray() = default;
  PoolArray(const Pool& mem, uint64_t n) { allocate(mem, n); }
  ~PoolArray() {
    if (ptr_) cudaFreeAsync(ptr_, stream_);
  }
  PoolArray(PoolArray&& o) noexcept
      : ptr_(std::exchange(o.ptr_, nullptr)),
        count_(std::exchange(o.count_, 0)),
        stream_(o.stream_) {}
  PoolArray& operator=(PoolArray&& o) noexcept {
    std::swap(ptr_, o.ptr_);
    std::swap(count_, o.count_);
    std::swap(stream_, o.stream_);
    return *this;
  }
  PoolArray(const PoolArray&) = delete;
  PoolArray& operator=(const PoolArray&) = delete;

  T* data() const { return ptr_; }
  size_t size() const { return count_; }

  // At least n elements (contents kept only when no growth); twice the size asked for, as the
  // levels' arrays grow over the first levels.
  T* grow(const Pool& mem, uint64_t n) {
    if (count_ >= n) return ptr_;
    if (ptr_) GVDP_CUDA_CHECK(cudaFreeAsync(ptr_, stream_));
    ptr_ = nullptr;
    count_ = 0;
    allocate(mem, 2 * n + 64);
    return ptr_;
  }

 private:
  void allocate(const Pool& mem, uint64_t count) {
    stream_ = mem.stream;
    if (count == 0) return;
    GVDP_CUDA_CHECK(cudaMallocFromPoolAsync(reinterpret_cast<void**>(&ptr_), count * sizeof(T),
                                            mem.pool, mem.stream));
    count_ = count;
  }

  T* ptr_ = nullptr;
  size_t count_ = 0;
  cudaStream_t stream_ = nullptr;
};

// CUB's two-call pattern on one grow-only temporary buffer: call(temp, bytes) sizes, then runs.
struct Cub {
  const Pool& mem;
  cudaStream_t stream;
  PoolArray<uint8_t> temp;

  template <class Call>
  void operator()(Call call) {
    size_t bytes = 0;
    GVDP_CUDA_CHECK(call(nullptr, bytes));
    void* t = temp.grow(mem, bytes > 0 ? bytes : 1);
    GVDP_CUDA_CHECK(call(t, bytes));
  }
  // out[i] = in[0] + ... + in[i - 1], over n elements (in[n - 1] is 0 where the total is wanted).
  template <class T>
  void exclusiveSum(const T* in, T* out, uint64_t n) {
    (*this)([&](void* t, size_t& b) {
      return cub::DeviceScan::ExclusiveSum(t, b, in, out, static_cast<int>(n), stream);
    });
  }
};

uint32_t readValue(const uint32_t* at, cudaStream_t stream) {
  uint32_t v = 0;
  readDevice(&v, at, sizeof v, stream);
  return v;
}

// One level's nodes, slots and events (kdtree_parallel.cpp's Level), in device arrays.
struct DeviceLevel {
  PoolArray<Box3f> box;
  PoolArray<uint32_t> triBegin;                // nodes + 1
  std::array<PoolArray<uint32_t>, 3> evBegin;  // nodes + 1 per axis
  PoolArray<uint32_t> tri, triOwner;           // per slot
  std::array<PoolArray<KdEvent>, 3> ev;        // triangleAndType: slot << 2 | type
  std::array<PoolArray<uint32_t>, 3> evOwner;  // per event
  uint64_t nodes = 0, slots = 0;
  std::array<uint64_t, 3> events{};
};

// Scratch arrays of a level (grow-only, kept across levels).
struct Scratch {
  PoolArray<KdEventCounts> before;
  PoolArray<KdSplit> runBest, best;
  PoolArray<uint32_t> runOwner, runs;
  PoolArray<uint32_t> split, rank, leafOffset;
  PoolArray<uint8_t> left, right;
  PoolArray<uint64_t> goes, slotScan;
  std::array<PoolArray<uint64_t>, 3> evScan;
  PoolArray<uint32_t> slotL, slotR, childCount, totals;
  PoolArray<KdNode> nodes;
  PoolArray<uint32_t> leafTriangles;
};

// totalsKernel's values, read back with one synchronisation.
std::array<uint32_t, 4> readTotals(const uint32_t* a, const uint32_t* b, const uint32_t* c,
                                   const uint32_t* d, uint32_t* totals, cudaStream_t s) {
  totalsKernel<<<1, 32, 0, s>>>(a, b, c, d, totals);
  checkLaunch();
  std::array<uint32_t, 4> v{};
  readDevice(v.data(), totals, sizeof v, s);
  return v;
}

void checkSize(uint64_t n) {
  GVDP_CHECK(n < (uint64_t{1} << 31) - 1, "kd-tree (GPU): ", n, " elements in one array");
}

// The root level: one node, slot t = triangle t, each axis's events sorted (kdRootEvents).
void rootLevel(const Mesh& mesh, DeviceLevel& l, Box3f& bounds, Cub& cub) {
  cudaStream_t s = cub.stream;
  const Pool& mem = cub.mem;
  auto n = static_cast<uint32_t>(mesh.triangleCount());
  checkSize(2 * uint64_t{n} + 1);
  PoolArray<Vec3f> vertices(mem, mesh.vertices.size());
  PoolArray<uint32_t> indices(mem, mesh.indices.size());
  writeDevice(vertices.data(), mesh.vertices.data(), mesh.vertices.size() * sizeof(Vec3f), s);
  writeDevice(indices.data(), mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t), s);
  PoolArray<Box3f> boxes(mem, n), root(mem, 1);
  triangleBoxesKernel<<<blocks(n), BLOCK, 0, s>>>(vertices.data(), indices.data(), n, boxes.data());
  checkLaunch();
  Box3f* boxesIn = boxes.data();
  Box3f* rootOut = root.data();
  cub([&](void* t, size_t& b) {
    return cub::DeviceReduce::Reduce(t, b, boxesIn, rootOut, static_cast<int>(n), MergeBoxes{},
                                     emptyBox(), s);
  });
  readDevice(&bounds, root.data(), sizeof bounds, s);

  l.nodes = 1;
  l.slots = n;
  writeDevice(l.box.grow(mem, 1), &bounds, sizeof bounds, s);
  const uint32_t triBegin[2] = {0, n};
  writeDevice(l.triBegin.grow(mem, 2), triBegin, sizeof triBegin, s);
  iotaKernel<<<blocks(n), BLOCK, 0, s>>>(l.tri.grow(mem, n), n);
  checkLaunch();
  fillDevice(l.triOwner.grow(mem, n), 0, n * sizeof(uint32_t), s);

  PoolArray<uint32_t> count(mem, n + 1), offset(mem, n + 1);
  PoolArray<KdEvent> unsorted(mem, 2 * uint64_t{n});
  PoolArray<uint64_t> keys(mem, 2 * uint64_t{n}), sortedKeys(mem, 2 * uint64_t{n});
  PoolArray<uint32_t> index(mem, 2 * uint64_t{n}), sortedIndex(mem, 2 * uint64_t{n});
  for (int axis = 0; axis < 3; ++axis) {
    rootEventCountKernel<<<blocks(n + 1), BLOCK, 0, s>>>(boxes.data(), n, axis, count.data());
    checkLaunch();
    cub.exclusiveSum(count.data(), offset.data(), n + 1);
    rootEventsKernel<<<blocks(n), BLOCK, 0, s>>>(boxes.data(), n, axis, offset.data(),
                                                 unsorted.data(), keys.data(), index.data());
    checkLaunch();
    uint32_t events = readValue(offset.data() + n, s);
    // Stable on the 34 bits of eventKey; equal keys keep triangle order: kdEventLess.
    uint64_t* keysIn = keys.data();
    uint64_t* keysOut = sortedKeys.data();
    uint32_t* indexIn = index.data();
    uint32_t* indexOut = sortedIndex.data();
    cub([&](void* t, size_t& b) {
      return cub::DeviceRadixSort::SortPairs(t, b, keysIn, keysOut, indexIn, indexOut,
                                             static_cast<int>(events), 0, 34, s);
    });
    gatherEventsKernel<<<blocks(events), BLOCK, 0, s>>>(unsorted.data(), sortedIndex.data(), events,
                                                        l.ev[axis].grow(mem, events));
    checkLaunch();
    const uint32_t evBegin[2] = {0, events};
    writeDevice(l.evBegin[axis].grow(mem, 2), evBegin, sizeof evBegin, s);
    fillDevice(l.evOwner[axis].grow(mem, events), 0, events * sizeof(uint32_t), s);
    l.events[axis] = events;
  }
  // the temporaries above return to the pool, in stream order
}

}  // namespace

KdTree buildKdTreeCuda(const Mesh& mesh) {
  OwnedGpuStream owned(createGpuStream());
  auto s = static_cast<cudaStream_t>(owned.get());
  Pool mem(s);
  Cub cub{mem, s, {}};
  KdTree tree;
  if (mesh.triangleCount() == 0) {  // the root is an empty leaf (as the CPU builders make it)
    tree.nodes = {kdLeaf(0, 0)};
    return tree;
  }
  DeviceLevel cur, next;
  Scratch x;
  rootLevel(mesh, cur, tree.bounds, cub);
  uint32_t nodeBase = 0;
  uint32_t* totals = x.totals.grow(mem, 4);
  uint32_t* runs = x.runs.grow(mem, 1);
  for (int depth = 0; cur.nodes > 0; ++depth) {
    const uint64_t m = cur.nodes;
    const auto m32 = static_cast<uint32_t>(m);
    checkSize(m + 1);
    KdSplit* best = x.best.grow(mem, m);
    noSplitKernel<<<blocks(m), BLOCK, 0, s>>>(m32, best);
    checkLaunch();

    // (1) the best split of every node: per axis, a scan of the event counts, every event
    // evaluated, the best of every node's events (a reduction by owner: betterSplit), merged
    // into the node's best over the axes
    for (int axis = 0; axis < 3; ++axis) {
      const uint64_t n = cur.events[axis];
      checkSize(n);
      const auto n32 = static_cast<uint32_t>(n);
      const uint32_t maxRuns = std::min(m32, n32);
      if (n == 0) continue;  // the nodes keep noSplit() on this axis
      KdEventCounts* before = x.before.grow(mem, n);
      KdSplit* runBest = x.runBest.grow(mem, m);
      uint32_t* runOwner = x.runOwner.grow(mem, m);
      const uint32_t* evBegin = cur.evBegin[axis].data();
      const uint32_t* evOwner = cur.evOwner[axis].data();
      const KdEvent* ev = cur.ev[axis].data();
      auto counts = thrust::make_transform_iterator(ev, CountsOf{});
      cub([&](void* t, size_t& b) {
        return cub::DeviceScan::ExclusiveScan(t, b, counts, before, AddCounts{},
                                              KdEventCounts{0, 0, 0}, static_cast<int>(n), s);
      });
      auto evaluated = thrust::make_transform_iterator(
          thrust::counting_iterator<uint32_t>(0),
          EvaluateEvent{ev, evOwner, evBegin, before, cur.triBegin.data(), cur.box.data(), axis});
      cub([&](void* t, size_t& b) {
        return cub::DeviceReduce::ReduceByKey(t, b, evOwner, runOwner, evaluated, runBest, runs,
                                              BestOf{}, static_cast<int>(n), s);
      });
      mergeRunsKernel<<<blocks(maxRuns), BLOCK, 0, s>>>(runOwner, runBest, runs, maxRuns, best);
      checkLaunch();
    }

    // (2) which nodes split; ranks among the split nodes, leaf triangle offsets; their totals
    uint32_t* split = x.split.grow(mem, m + 1);
    uint32_t* rank = x.rank.grow(mem, m + 1);
    uint32_t* leafOffset = x.leafOffset.grow(mem, m + 1);
    uint64_t* flags = x.goes.grow(mem, m + 1);
    uint64_t* flagScan = x.slotScan.grow(mem, m + 1);
    decideKernel<<<blocks(m + 1), BLOCK, 0, s>>>(cur.box.data(), cur.triBegin.data(), best, m32,
                                                 depth, split, flags);
    checkLaunch();
    cub.exclusiveSum(flags, flagScan, m + 1);
    unpackKernel<<<blocks(m + 1), BLOCK, 0, s>>>(flagScan, m32, rank, leafOffset);
    checkLaunch();
    const auto levelTotals = readTotals(rank + m, leafOffset + m, nullptr, nullptr, totals, s);
    const uint32_t splits = levelTotals[0];
    const uint32_t leafRefs = levelTotals[1];

    // (3) the sides of every slot of a split node
    const uint64_t slots = cur.slots;
    const auto slots32 = static_cast<uint32_t>(slots);
    uint8_t* left = x.left.grow(mem, slots);
    uint8_t* right = x.right.grow(mem, slots);
    if (splits > 0) {
      fillDevice(left, 0, slots, s);
      fillDevice(right, 0, slots, s);
      for (int axis = 0; axis < 3; ++axis) {
        const uint64_t n = cur.events[axis];
        sidesKernel<<<blocks(n), BLOCK, 0, s>>>(cur.ev[axis].data(), static_cast<uint32_t>(n),
                                                cur.evOwner[axis].data(), split, best, axis, left,
                                                right);
        checkLaunch();
      }
    }

    // (4) the level's nodes and leaves (read back below, with the next level's totals)
    const uint32_t nextBase = nodeBase + m32;
    const auto leafBase = static_cast<uint32_t>(tree.leafTriangles.size());
    GVDP_CHECK(uint64_t{nextBase} + 2 * uint64_t{splits} <= KD_MAX_INDEX &&
                   uint64_t{leafBase} + leafRefs <= KD_MAX_INDEX,
               "kd-tree past 2^30 nodes or leaf references");
    KdNode* nodes = x.nodes.grow(mem, m);
    uint32_t* leafTriangles = x.leafTriangles.grow(mem, leafRefs);
    nodesKernel<<<blocks(m), BLOCK, 0, s>>>(split, best, rank, leafOffset, cur.triBegin.data(), m32,
                                            nextBase, leafBase, nodes);
    checkLaunch();
    leafTrianglesKernel<<<blocks(slots), BLOCK, 0, s>>>(cur.tri.data(), cur.triOwner.data(),
                                                        slots32, split, cur.triBegin.data(),
                                                        leafOffset, leafTriangles);
    checkLaunch();
    auto readLevel = [&] {
      tree.nodes.resize(nextBase + 2 * size_t{splits});
      tree.leafTriangles.resize(leafBase + size_t{leafRefs});
      readDevice(tree.nodes.data() + nodeBase, nodes, m * sizeof(KdNode), s);
      if (leafRefs > 0)
        readDevice(tree.leafTriangles.data() + leafBase, leafTriangles, leafRefs * sizeof(uint32_t),
                   s);
    };
    if (splits == 0) {
      readLevel();
      break;
    }

    // (5) the next level: boxes; slots, then events, placed by scans of their side flags
    const uint64_t children = 2 * uint64_t{splits};
    checkSize(children + 1);
    next.nodes = children;
    childBoxesKernel<<<blocks(m), BLOCK, 0, s>>>(cur.box.data(), split, best, rank, m32,
                                                 next.box.grow(mem, children));
    checkLaunch();
    uint32_t* childCount = x.childCount.grow(mem, children + 1);
    fillDevice(childCount + children, 0, sizeof(uint32_t), s);
    uint64_t* goes = x.goes.grow(mem, slots + 1);
    uint64_t* slotScan = x.slotScan.grow(mem, slots + 1);
    goesKernel<<<blocks(slots + 1), BLOCK, 0, s>>>(nullptr, slots32, cur.triOwner.data(), split,
                                                   left, right, goes);
    checkLaunch();
    cub.exclusiveSum(goes, slotScan, slots + 1);
    childCountsKernel<<<blocks(m), BLOCK, 0, s>>>(split, rank, cur.triBegin.data(), slotScan, m32,
                                                  childCount);
    checkLaunch();
    uint32_t* nextTriBegin = next.triBegin.grow(mem, children + 1);
    cub.exclusiveSum(childCount, nextTriBegin, children + 1);
    std::array<uint64_t*, 3> evScan{};
    std::array<uint32_t*, 3> nextEvBegin{};
    for (int axis = 0; axis < 3; ++axis) {
      const uint64_t n = cur.events[axis];
      // goes is reused: the stream orders its uses
      uint64_t* evGoes = x.goes.grow(mem, n + 1);
      evScan[axis] = x.evScan[axis].grow(mem, n + 1);
      goesKernel<<<blocks(n + 1), BLOCK, 0, s>>>(cur.ev[axis].data(), static_cast<uint32_t>(n),
                                                 cur.triOwner.data(), split, left, right, evGoes);
      checkLaunch();
      cub.exclusiveSum(evGoes, evScan[axis], n + 1);
      childCountsKernel<<<blocks(m), BLOCK, 0, s>>>(split, rank, cur.evBegin[axis].data(),
                                                    evScan[axis], m32, childCount);
      checkLaunch();
      nextEvBegin[axis] = next.evBegin[axis].grow(mem, children + 1);
      cub.exclusiveSum(childCount, nextEvBegin[axis], children + 1);
    }
    readLevel();
    const auto nextTotals =
        readTotals(nextTriBegin + children, nextEvBegin[0] + children, nextEvBegin[1] + children,
                   nextEvBegin[2] + children, totals, s);
    next.slots = nextTotals[0];
    checkSize(next.slots);
    GVDP_CHECK(next.slots <= KD_MAX_INDEX, "kd-tree (GPU): past 2^30 slots in one level");
    uint32_t* slotL = x.slotL.grow(mem, slots);
    uint32_t* slotR = x.slotR.grow(mem, slots);
    scatterSlotsKernel<<<blocks(slots), BLOCK, 0, s>>>(
        cur.tri.data(), cur.triOwner.data(), slots32, split, rank, cur.triBegin.data(), left, right,
        slotScan, nextTriBegin, next.tri.grow(mem, next.slots), next.triOwner.grow(mem, next.slots),
        slotL, slotR);
    checkLaunch();
    for (int axis = 0; axis < 3; ++axis) {
      const uint64_t n = cur.events[axis];
      const uint64_t nextEvents = nextTotals[1 + axis];
      checkSize(nextEvents);
      next.events[axis] = nextEvents;
      scatterEventsKernel<<<blocks(n), BLOCK, 0, s>>>(
          cur.ev[axis].data(), static_cast<uint32_t>(n), cur.evOwner[axis].data(), split, rank,
          cur.evBegin[axis].data(), left, right, evScan[axis], nextEvBegin[axis], slotL, slotR,
          next.ev[axis].grow(mem, nextEvents), next.evOwner[axis].grow(mem, nextEvents));
      checkLaunch();
    }
    std::swap(cur, next);
    nodeBase = nextBase;
  }
  GVDP_CUDA_CHECK(cudaStreamSynchronize(s));
  return tree;
}

}  // namespace gvdp::detail
