// Seed 004's level-by-level kd-tree builder on the GPU (kdtree_build.h buildKdTreeCuda): the
// steps of kdtree_parallel.cpp, one CUB call or one element-wise kernel each, over the same flat
// arrays (a level's nodes, its slots, its events), the rules being kdtree.h's GVDP_HD functions,
// with the three axes' events in one array (Segment) so that each step is one launch for all
// three. Nodes and leaf triangles are written in the same places as the parallel builder's, so
// the two trees are equal even in storage. On the device: the triangles' boxes (from the
// uploaded vertices and indices), the root box (cub::DeviceReduce), the root events (counted,
// cub::DeviceScan, written axis by axis in triangle order, then one stable
// cub::DeviceRadixSort on (axis, eventKey): kdEventLess's order per axis), every level, and the
// tree itself, downloaded once at the end. A node's best split is a reduction by key over the
// events' segments (cub::DeviceReduce::ReduceByKey, the candidates evaluated as CUB reads them).
// The host reads back one thing a level, its totals (to size the next level's arrays); until
// then it sizes by bounds. The arrays come from a memory pool of the build's own, grown in
// stream order. Built with --fmad=false (src/CMakeLists.txt) on top of the explicitly rounded
// operations of base/rounded_math.h.
#include <cuda_runtime.h>

#include <thrust/iterator/counting_iterator.h>
#include <thrust/iterator/transform_iterator.h>
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_reduce.cuh>
#include <cub/device/device_scan.cuh>
#include <thread>
#include <utility>

#include "gvdp/base/cuda_util.h"
#include "gvdp/base/gpu.h"
#include "gvdp/mesh/kdtree_build.h"

namespace gvdp::detail {
namespace {

constexpr int BLOCK = 256;

// --- the level's layout ------------------------------------------------------------------------
// A level's events of the three axes are one array: the axis-0 events of every node, node by
// node, then the axis-1 and axis-2 ones. Event i belongs to segment key[i] = axis * stride + node
// (stride >= the level's nodes, known to the host before the level's count is), whose events are
// [evBegin[key], evBegin[key + 1]); keys ascend along the array, so one scan, one reduction by
// key and one element-wise kernel serve the three axes at once.
struct Segment {
  uint32_t axis, node;
};
__host__ __device__ __forceinline__ Segment segmentOf(uint32_t key, uint32_t stride) {
  uint32_t axis = key / stride;
  return {axis, key - axis * stride};
}

// Two counts scanned at once as one uint64_t (low: the first, high: the second; neither total
// reaches 2^31, so no carry crosses).
__host__ __device__ __forceinline__ uint32_t scanL(const uint64_t* scan, uint32_t i) {
  return static_cast<uint32_t>(scan[i]);
}
__host__ __device__ __forceinline__ uint32_t scanR(const uint64_t* scan, uint32_t i) {
  return static_cast<uint32_t>(scan[i] >> 32);
}

// --- kernels (one thread per element; i < n) ------------------------------------------------

__global__ void triangleBoxesKernel(const Vec3f* vertices, const uint32_t* indices, uint32_t n,
                                    Box3f* boxes) {
  uint32_t t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= n) return;
  boxes[t] = kdTriangleBox(vertices[indices[3 * t]], vertices[indices[3 * t + 1]],
                           vertices[indices[3 * t + 2]]);
}

// Element a * n + t: triangle t's events on axis a (1 for a triangle flat on the axis, else 2);
// count[3n] = 0 (the scan's total lands there).
__global__ void rootEventCountKernel(const Box3f* boxes, uint32_t n, uint32_t* count) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i > 3 * n) return;
  if (i == 3 * n) {
    count[i] = 0;
    return;
  }
  uint32_t axis = i / n, t = i - axis * n;
  count[i] = component(boxes[t].lo, axis) == component(boxes[t].hi, axis) ? 1u : 2u;
}

// The events of kdRootEvents, axis by axis in triangle order, with their sort keys (eventKey
// below the axis) and their indices; evBegin: the axes' first events and the total.
__global__ void rootEventsKernel(const Box3f* boxes, uint32_t n, const uint32_t* offset,
                                 KdEvent* ev, uint64_t* key, uint32_t* index, uint32_t* evBegin) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < 4) evBegin[i] = offset[i * n];
  if (i >= 3 * n) return;
  uint32_t axis = i / n, t = i - axis * n;
  float lo = component(boxes[t].lo, axis), hi = component(boxes[t].hi, axis);
  uint32_t o = offset[i];
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
    key[o + k] = uint64_t{axis} << 34 | eventKey(e[k]);
    index[o + k] = o + k;
  }
}

// The sorted root events and their segment keys (the root's segments are its axes).
__global__ void gatherEventsKernel(const KdEvent* in, const uint64_t* sortedKey,
                                   const uint32_t* index, uint32_t n, KdEvent* out,
                                   uint32_t* outKey) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  out[i] = in[index[i]];
  outKey[i] = static_cast<uint32_t>(sortedKey[i] >> 34);
}

__global__ void iotaKernel(uint32_t* a, uint32_t n) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) a[i] = i;
}

// (1) an event's counts (the scan's input) and its candidate (evaluateEvent, with its segment's
// counts before it: the reduction's input), computed where CUB reads them (no arrays between).
struct CountsOf {
  __host__ __device__ KdEventCounts operator()(const KdEvent& e) const { return countsOf(e); }
};
struct EvaluateEvent {
  const KdEvent* ev;
  const uint32_t* key;
  const uint32_t* evBegin;
  const KdEventCounts* before;
  const uint32_t* triBegin;
  const Box3f* box;
  uint32_t stride;
  __host__ __device__ KdSplit operator()(uint32_t i) const {
    uint32_t k = key[i], b = evBegin[k];
    Segment s = segmentOf(k, stride);
    return evaluateEvent(ev, i, b, evBegin[k + 1], before[i] - before[b],
                         triBegin[s.node + 1] - triBegin[s.node], box[s.node],
                         static_cast<int>(s.axis));
  }
};

__global__ void noSplitKernel(uint32_t m, KdSplit* best) {
  uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j < m) best[j] = noSplit();
}

// The best of every run (cub::DeviceReduce::ReduceByKey over the keys: one run per segment with
// events) to its segment; a segment without events keeps noSplit(), as a reduction of its empty
// segment starting from noSplit() would give.
__global__ void scatterRunsKernel(const uint32_t* runKey, const KdSplit* runBest,
                                  const uint32_t* runs, uint32_t maxRuns, KdSplit* axisBest) {
  uint32_t r = blockIdx.x * blockDim.x + threadIdx.x;
  if (r < maxRuns && r < *runs) axisBest[runKey[r]] = runBest[r];
}

// (2) a node's best over its axes (betterSplit, a total order: any order of merging gives it),
// and the leaf rule: flags[j] packs (split, leaf triangles) for one scan; flags[m] = 0.
__global__ void decideKernel(const Box3f* box, const uint32_t* triBegin, const KdSplit* axisBest,
                             uint32_t m, uint32_t stride, int depth, KdSplit* best, uint32_t* split,
                             uint64_t* flags) {
  uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j > m) return;
  if (j == m) {
    flags[m] = 0;
    return;
  }
  KdSplit b = noSplit();
  for (uint32_t axis = 0; axis < 3; ++axis)
    if (betterSplit(axisBest[axis * stride + j], b)) b = axisBest[axis * stride + j];
  uint32_t n = triBegin[j + 1] - triBegin[j];
  bool s = shouldSplit(box[j], n, depth, b);
  best[j] = b;
  split[j] = s;
  flags[j] = s ? 1u : uint64_t{n} << 32;
}

// (3) the sides of every slot of a split node, from its split axis's events (one writer each).
__global__ void sidesKernel(const KdEvent* ev, const uint32_t* key, uint32_t n, uint32_t stride,
                            const uint32_t* split, const KdSplit* best, uint8_t* left,
                            uint8_t* right) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  Segment s = segmentOf(key[i], stride);
  if (!split[s.node] || best[s.node].axis != static_cast<int>(s.axis)) return;
  KdEvent e = ev[i];
  uint32_t sides = eventSides(e, best[s.node].pos), slot = eventTriangle(e), type = eventType(e);
  if (type != KD_EVENT_END) left[slot] = (sides & KD_LEFT) != 0;
  if (type != KD_EVENT_START) right[slot] = (sides & KD_RIGHT) != 0;
}

// (4) the level's nodes into the tree (children: the next level's nodes nextBase + 2 rank, +1;
// rank and leaf offset from decideKernel's scan), and the children's boxes.
__global__ void nodesKernel(const uint32_t* split, const KdSplit* best, const uint64_t* flagScan,
                            const uint32_t* triBegin, const Box3f* box, uint32_t m,
                            uint32_t nodeBase, uint32_t leafBase, KdNode* nodes, Box3f* next) {
  uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j >= m) return;
  uint32_t rank = scanL(flagScan, j);
  if (!split[j]) {
    nodes[nodeBase + j] = kdLeaf(leafBase + scanR(flagScan, j), triBegin[j + 1] - triBegin[j]);
    return;
  }
  KdSplit b = best[j];
  nodes[nodeBase + j] = kdInterior(b.axis, b.pos, nodeBase + m + 2 * rank);
  next[2 * rank] = leftBox(box[j], b.axis, b.pos);
  next[2 * rank + 1] = rightBox(box[j], b.axis, b.pos);
}

// (4, 5) Over the slots, then the events, then one more element: a leaf's slot writes its
// triangle into the tree (a node's slots hold ascending triangle ids, the root's 0..n-1 and
// every compaction keeping their order, so a leaf's list needs no sort); every element flags
// "goes to the left / right child" (packed for one scan; the last element 0). The slots' and the
// events' flags are scanned together: each use subtracts the scan at its segment's start.
__global__ void placeKernel(const uint32_t* tri, const uint32_t* triOwner, uint32_t slots,
                            const KdEvent* ev, uint32_t events, const uint32_t* split,
                            const uint32_t* triBegin, const uint64_t* flagScan, const uint8_t* left,
                            const uint8_t* right, uint32_t* leafTriangles, uint64_t* goes) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i > slots + events) return;
  if (i == slots + events) {
    goes[i] = 0;
    return;
  }
  uint32_t slot = i < slots ? i : eventTriangle(ev[i - slots]);
  uint32_t j = triOwner[slot];
  bool s = split[j] != 0;
  if (i < slots && !s) leafTriangles[scanR(flagScan, j) + i - triBegin[j]] = tri[i];
  goes[i] = uint64_t{s && left[slot]} | uint64_t{s && right[slot]} << 32;
}

// (5) the children's slot and event counts, in the next level's order (children 2 rank, +1;
// event segments axis * nextStride + child), out of the flags' scan.
__global__ void childCountsKernel(const uint32_t* split, const uint64_t* flagScan,
                                  const uint32_t* triBegin, const uint32_t* evBegin,
                                  const uint64_t* goesScan, uint32_t m, uint32_t slots,
                                  uint32_t stride, uint32_t nextStride, uint32_t* childSlots,
                                  uint32_t* childEvents) {
  uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j >= m || !split[j]) return;
  uint32_t c = 2 * scanL(flagScan, j), b = triBegin[j], e = triBegin[j + 1];
  childSlots[c] = scanL(goesScan, e) - scanL(goesScan, b);
  childSlots[c + 1] = scanR(goesScan, e) - scanR(goesScan, b);
  for (uint32_t axis = 0; axis < 3; ++axis) {
    uint32_t k = axis * stride + j;
    b = slots + evBegin[k];
    e = slots + evBegin[k + 1];
    childEvents[axis * nextStride + c] = scanL(goesScan, e) - scanL(goesScan, b);
    childEvents[axis * nextStride + c + 1] = scanR(goesScan, e) - scanR(goesScan, b);
  }
}

// The level's totals for the host (one read-back a level): split nodes, leaf references, and
// the next level's slots and events.
__global__ void totalsKernel(const uint64_t* flagScan, uint32_t m, const uint32_t* nextTriBegin,
                             const uint32_t* nextEvBegin, uint32_t nextStride, uint32_t* out) {
  if (threadIdx.x != 0) return;
  out[0] = scanL(flagScan, m);
  out[1] = scanR(flagScan, m);
  out[2] = nextTriBegin[nextStride];
  out[3] = nextEvBegin[3 * nextStride];
}

// (6) the slots placed in their children's segments, order kept ...
__global__ void scatterSlotsKernel(const uint32_t* tri, const uint32_t* triOwner, uint32_t slots,
                                   const uint32_t* split, const uint64_t* flagScan,
                                   const uint32_t* triBegin, const uint8_t* left,
                                   const uint8_t* right, const uint64_t* goesScan,
                                   const uint32_t* nextBegin, uint32_t* nextTri,
                                   uint32_t* nextOwner, uint32_t* slotL, uint32_t* slotR) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= slots) return;
  uint32_t j = triOwner[i];
  if (!split[j]) return;
  uint32_t b = triBegin[j], c = 2 * scanL(flagScan, j);
  if (left[i]) {
    uint32_t dst = nextBegin[c] + scanL(goesScan, i) - scanL(goesScan, b);
    nextTri[dst] = tri[i];
    nextOwner[dst] = c;
    slotL[i] = dst;
  }
  if (right[i]) {
    uint32_t dst = nextBegin[c + 1] + scanR(goesScan, i) - scanR(goesScan, b);
    nextTri[dst] = tri[i];
    nextOwner[dst] = c + 1;
    slotR[i] = dst;
  }
}

// ... and the events likewise, renamed to their slots in the children.
__global__ void scatterEventsKernel(const KdEvent* ev, const uint32_t* key, uint32_t n,
                                    uint32_t slots, uint32_t stride, uint32_t nextStride,
                                    const uint32_t* split, const uint64_t* flagScan,
                                    const uint32_t* evBegin, const uint8_t* left,
                                    const uint8_t* right, const uint64_t* goesScan,
                                    const uint32_t* nextBegin, const uint32_t* slotL,
                                    const uint32_t* slotR, KdEvent* nextEv, uint32_t* nextKey) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  uint32_t k = key[i];
  Segment s = segmentOf(k, stride);
  if (!split[s.node]) return;
  KdEvent e = ev[i];
  uint32_t slot = eventTriangle(e), c = 2 * scanL(flagScan, s.node);
  uint32_t at = slots + i, first = slots + evBegin[k];
  if (left[slot]) {
    uint32_t nk = s.axis * nextStride + c;
    uint32_t dst = nextBegin[nk] + scanL(goesScan, at) - scanL(goesScan, first);
    nextEv[dst] = {e.pos, slotL[slot] << 2 | eventType(e)};
    nextKey[dst] = nk;
  }
  if (right[slot]) {
    uint32_t nk = s.axis * nextStride + c + 1;
    uint32_t dst = nextBegin[nk] + scanR(goesScan, at) - scanR(goesScan, first);
    nextEv[dst] = {e.pos, slotR[slot] << 2 | eventType(e)};
    nextKey[dst] = nk;
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
  // At least n elements, the first `kept` kept (copied in stream order when it grows).
  T* growKeeping(const Pool& mem, uint64_t n, uint64_t kept) {
    if (count_ >= n) return ptr_;
    PoolArray bigger(mem, 2 * n + 64);
    if (kept > 0)
      GVDP_CUDA_CHECK(cudaMemcpyAsync(bigger.ptr_, ptr_, kept * sizeof(T), cudaMemcpyDeviceToDevice,
                                      mem.stream));
    *this = std::move(bigger);  // the old array is freed to the pool in stream order
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

// One level's nodes, slots and events (kdtree_parallel.cpp's Level, the three axes' events in
// one array: see Segment), in device arrays.
struct DeviceLevel {
  PoolArray<Box3f> box;
  PoolArray<uint32_t> triBegin;  // nodes + 1 (or more: the entries past the nodes hold the total)
  PoolArray<uint32_t> evBegin;   // 3 stride + 1: per segment key
  PoolArray<uint32_t> tri, triOwner;  // per slot
  PoolArray<KdEvent> ev;              // triangleAndType: slot << 2 | type
  PoolArray<uint32_t> key;            // per event: its segment, axis * stride + node
  uint64_t nodes = 0, stride = 1, slots = 0, events = 0;
};

// Scratch arrays of a level (grow-only, kept across levels), and the tree being built.
struct Scratch {
  PoolArray<KdEventCounts> before;
  PoolArray<KdSplit> runBest, axisBest, best;
  PoolArray<uint32_t> runKey, runs;
  PoolArray<uint32_t> split;
  PoolArray<uint64_t> flags, flagScan;
  PoolArray<uint8_t> sides;  // left flags, then right flags
  PoolArray<uint64_t> goes, goesScan;
  PoolArray<uint32_t> childSlots, childEvents, slotL, slotR, totals;
  PoolArray<KdNode> nodes;            // the tree's, level after level
  PoolArray<uint32_t> leafTriangles;  // the tree's
};

void checkSize(uint64_t n) {
  GVDP_CHECK(n < (uint64_t{1} << 31) - 1, "kd-tree (GPU): ", n, " elements in one array");
}

// The root level: one node, slot t = triangle t, each axis's events sorted (kdRootEvents): the
// three axes' events made in one kernel and sorted in one stable radix sort on (axis, eventKey).
void rootLevel(const Mesh& mesh, DeviceLevel& l, Box3f& bounds, Cub& cub) {
  cudaStream_t s = cub.stream;
  const Pool& mem = cub.mem;
  auto n = static_cast<uint32_t>(mesh.triangleCount());
  checkSize(6 * uint64_t{n} + 1);
  PoolArray<Vec3f> vertices(mem, mesh.vertices.size());
  PoolArray<uint32_t> indices(mem, mesh.indices.size());
  writeDevice(vertices.data(), mesh.vertices.data(), mesh.vertices.size() * sizeof(Vec3f), s);
  writeDevice(indices.data(), mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t), s);
  PoolArray<Box3f> boxes(mem, n);
  triangleBoxesKernel<<<blocks(n), BLOCK, 0, s>>>(vertices.data(), indices.data(), n, boxes.data());
  checkLaunch();
  Box3f* boxesIn = boxes.data();
  Box3f* rootOut = l.box.grow(mem, 1);
  cub([&](void* t, size_t& b) {
    return cub::DeviceReduce::Reduce(t, b, boxesIn, rootOut, static_cast<int>(n), MergeBoxes{},
                                     emptyBox(), s);
  });
  l.nodes = 1;
  l.stride = 1;
  l.slots = n;
  const uint32_t triBegin[2] = {0, n};
  writeDevice(l.triBegin.grow(mem, 2), triBegin, sizeof triBegin, s);
  iotaKernel<<<blocks(n), BLOCK, 0, s>>>(l.tri.grow(mem, n), n);
  checkLaunch();
  fillDevice(l.triOwner.grow(mem, n), 0, n * sizeof(uint32_t), s);

  const uint64_t most = 6 * uint64_t{n};
  PoolArray<uint32_t> count(mem, 3 * uint64_t{n} + 1), offset(mem, 3 * uint64_t{n} + 1);
  PoolArray<KdEvent> unsorted(mem, most);
  PoolArray<uint64_t> keys(mem, most), sortedKeys(mem, most);
  PoolArray<uint32_t> index(mem, most), sortedIndex(mem, most);
  rootEventCountKernel<<<blocks(3 * uint64_t{n} + 1), BLOCK, 0, s>>>(boxes.data(), n, count.data());
  checkLaunch();
  cub.exclusiveSum(count.data(), offset.data(), 3 * uint64_t{n} + 1);
  uint32_t* evBegin = l.evBegin.grow(mem, 4);
  rootEventsKernel<<<blocks(3 * uint64_t{n}), BLOCK, 0, s>>>(
      boxes.data(), n, offset.data(), unsorted.data(), keys.data(), index.data(), evBegin);
  checkLaunch();
  readDevice(&bounds, rootOut, sizeof bounds, s);
  const uint32_t events = readValue(offset.data() + 3 * uint64_t{n}, s);
  // Stable on the 36 bits of (axis, eventKey); equal keys keep triangle order: kdEventLess.
  uint64_t* keysIn = keys.data();
  uint64_t* keysOut = sortedKeys.data();
  uint32_t* indexIn = index.data();
  uint32_t* indexOut = sortedIndex.data();
  cub([&](void* t, size_t& b) {
    return cub::DeviceRadixSort::SortPairs(t, b, keysIn, keysOut, indexIn, indexOut,
                                           static_cast<int>(events), 0, 36, s);
  });
  gatherEventsKernel<<<blocks(events), BLOCK, 0, s>>>(
      unsorted.data(), sortedKeys.data(), sortedIndex.data(), events, l.ev.grow(mem, events),
      l.key.grow(mem, events));
  checkLaunch();
  l.events = events;
  // the temporaries above return to the pool, in stream order
}

}  // namespace

KdTree buildKdTreeCuda(const Mesh& mesh, KdBuildPhases* phases) {
  auto start = std::chrono::steady_clock::now();
  auto msSince = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
  };
  KdBuildPhases ph;
  OwnedGpuStream owned(createGpuStream());
  auto s = static_cast<cudaStream_t>(owned.get());
  Pool mem(s);
  Cub cub{mem, s, {}};
  KdTree tree;
  if (mesh.triangleCount() == 0) {  // the root is an empty leaf (as the CPU builders make it)
    tree.nodes = {kdLeaf(0, 0)};
    return tree;
  }
  // The tree's host memory is touched by a helper thread while the GPU builds: a fresh host
  // page's first touch cost as much as the copy into it (the download of a 1.2 M-triangle tree,
  // 72 MB, took 17-27 ms into new vectors, measured; 42 ms through a kept page-locked buffer and
  // a copy into new vectors). Sized by what the trees here hold per triangle (4.6-4.9 nodes,
  // 4.7-5.2 leaf references), cut or grown to the real sizes at the download.
  const size_t expected = 6 * mesh.triangleCount();
  std::jthread touch([&tree, expected] {
    tree.nodes.resize(expected);
    tree.leafTriangles.resize(expected);
  });
  DeviceLevel cur, next;
  Scratch x;
  rootLevel(mesh, cur, tree.bounds, cub);
  ph.rootMs = msSince(start);
  uint64_t nodeBase = 0, leafBase = 0;
  uint32_t* runs = x.runs.grow(mem, 1);
  uint32_t* totals = x.totals.grow(mem, 4);
  // Every level: one read-back (its totals), at its end. Until then the host sizes arrays by
  // bounds: at most m split nodes, 2 m children, `slots` leaf references.
  for (int depth = 0;; ++depth) {
    const uint64_t m = cur.nodes, stride = cur.stride, slots = cur.slots, events = cur.events;
    const uint64_t nextStride = 2 * m;
    checkSize(3 * nextStride + 1);
    checkSize(slots + events + 1);
    const auto m32 = static_cast<uint32_t>(m), stride32 = static_cast<uint32_t>(stride);
    const auto slots32 = static_cast<uint32_t>(slots), events32 = static_cast<uint32_t>(events);
    const auto nextStride32 = static_cast<uint32_t>(nextStride);
    const uint32_t* triBegin = cur.triBegin.data();
    const uint32_t* evBegin = cur.evBegin.data();

    // (1) the best split of every segment (node and axis): a scan of the event counts, every
    // event evaluated, the best of each segment's events (a reduction by key: betterSplit)
    KdSplit* axisBest = x.axisBest.grow(mem, 3 * stride);
    noSplitKernel<<<blocks(3 * stride), BLOCK, 0, s>>>(static_cast<uint32_t>(3 * stride), axisBest);
    checkLaunch();
    if (events > 0) {
      const auto maxRuns = static_cast<uint32_t>(std::min(events, 3 * m));
      KdEventCounts* before = x.before.grow(mem, events);
      KdSplit* runBest = x.runBest.grow(mem, maxRuns);
      uint32_t* runKey = x.runKey.grow(mem, maxRuns);
      const KdEvent* ev = cur.ev.data();
      const uint32_t* key = cur.key.data();
      auto counts = thrust::make_transform_iterator(ev, CountsOf{});
      cub([&](void* t, size_t& b) {
        return cub::DeviceScan::ExclusiveScan(t, b, counts, before, AddCounts{},
                                              KdEventCounts{0, 0, 0}, static_cast<int>(events), s);
      });
      auto evaluated = thrust::make_transform_iterator(
          thrust::counting_iterator<uint32_t>(0),
          EvaluateEvent{ev, key, evBegin, before, triBegin, cur.box.data(), stride32});
      cub([&](void* t, size_t& b) {
        return cub::DeviceReduce::ReduceByKey(t, b, key, runKey, evaluated, runBest, runs, BestOf{},
                                              static_cast<int>(events), s);
      });
      scatterRunsKernel<<<blocks(maxRuns), BLOCK, 0, s>>>(runKey, runBest, runs, maxRuns, axisBest);
      checkLaunch();
    }

    // (2) every node's best, which nodes split; ranks among the split nodes and leaf offsets
    KdSplit* best = x.best.grow(mem, m);
    uint32_t* split = x.split.grow(mem, m);
    uint64_t* flags = x.flags.grow(mem, m + 1);
    uint64_t* flagScan = x.flagScan.grow(mem, m + 1);
    decideKernel<<<blocks(m + 1), BLOCK, 0, s>>>(cur.box.data(), triBegin, axisBest, m32, stride32,
                                                 depth, best, split, flags);
    checkLaunch();
    cub.exclusiveSum(flags, flagScan, m + 1);

    // (3) the sides of every slot of a split node
    uint8_t* left = x.sides.grow(mem, 2 * slots);
    uint8_t* right = left + slots;
    fillDevice(left, 0, 2 * slots, s);
    sidesKernel<<<blocks(events), BLOCK, 0, s>>>(cur.ev.data(), cur.key.data(), events32, stride32,
                                                 split, best, left, right);
    checkLaunch();

    // (4) the level's nodes and leaves into the tree; the children's boxes
    KdNode* nodes = x.nodes.growKeeping(mem, nodeBase + 3 * m, nodeBase);
    uint32_t* leaves = x.leafTriangles.growKeeping(mem, leafBase + slots, leafBase);
    nodesKernel<<<blocks(m), BLOCK, 0, s>>>(
        split, best, flagScan, triBegin, cur.box.data(), m32, static_cast<uint32_t>(nodeBase),
        static_cast<uint32_t>(leafBase), nodes, next.box.grow(mem, nextStride));
    checkLaunch();

    // (5) the slots' and the events' side flags (and the leaves' triangles), scanned together;
    // the children's counts and their segments in the next level
    uint64_t* goes = x.goes.grow(mem, slots + events + 1);
    uint64_t* goesScan = x.goesScan.grow(mem, slots + events + 1);
    placeKernel<<<blocks(slots + events + 1), BLOCK, 0, s>>>(
        cur.tri.data(), cur.triOwner.data(), slots32, cur.ev.data(), events32, split, triBegin,
        flagScan, left, right, leaves + leafBase, goes);
    checkLaunch();
    cub.exclusiveSum(goes, goesScan, slots + events + 1);
    uint32_t* childSlots = x.childSlots.grow(mem, nextStride + 1);
    uint32_t* childEvents = x.childEvents.grow(mem, 3 * nextStride + 1);
    fillDevice(childSlots, 0, (nextStride + 1) * sizeof(uint32_t), s);
    fillDevice(childEvents, 0, (3 * nextStride + 1) * sizeof(uint32_t), s);
    childCountsKernel<<<blocks(m), BLOCK, 0, s>>>(split, flagScan, triBegin, evBegin, goesScan, m32,
                                                  slots32, stride32, nextStride32, childSlots,
                                                  childEvents);
    checkLaunch();
    uint32_t* nextTriBegin = next.triBegin.grow(mem, nextStride + 1);
    uint32_t* nextEvBegin = next.evBegin.grow(mem, 3 * nextStride + 1);
    cub.exclusiveSum(childSlots, nextTriBegin, nextStride + 1);
    cub.exclusiveSum(childEvents, nextEvBegin, 3 * nextStride + 1);
    totalsKernel<<<1, 32, 0, s>>>(flagScan, m32, nextTriBegin, nextEvBegin, nextStride32, totals);
    checkLaunch();
    std::array<uint32_t, 4> t{};
    readDevice(t.data(), totals, sizeof t, s);
    const uint64_t splits = t[0], leafRefs = t[1];
    GVDP_CHECK(nodeBase + m + 2 * splits <= KD_MAX_INDEX && leafBase + leafRefs <= KD_MAX_INDEX,
               "kd-tree past 2^30 nodes or leaf references");
    if (splits == 0) {
      ph.levels = depth + 1;
      ph.levelsMs = msSince(start) - ph.rootMs;
      touch.join();
      tree.nodes.resize(nodeBase + m);
      tree.leafTriangles.resize(leafBase + leafRefs);
      readDevice(tree.nodes.data(), nodes, tree.nodes.size() * sizeof(KdNode), s);
      if (!tree.leafTriangles.empty())
        readDevice(tree.leafTriangles.data(), leaves, tree.leafTriangles.size() * sizeof(uint32_t),
                   s);
      break;
    }

    // (6) the next level: slots, then events, placed in their children's segments
    next.nodes = 2 * splits;
    next.stride = nextStride;
    next.slots = t[2];
    next.events = t[3];
    checkSize(next.slots);
    checkSize(next.events);
    GVDP_CHECK(next.slots <= KD_MAX_INDEX, "kd-tree (GPU): past 2^30 slots in one level");
    uint32_t* slotL = x.slotL.grow(mem, slots);
    uint32_t* slotR = x.slotR.grow(mem, slots);
    scatterSlotsKernel<<<blocks(slots), BLOCK, 0, s>>>(
        cur.tri.data(), cur.triOwner.data(), slots32, split, flagScan, triBegin, left, right,
        goesScan, nextTriBegin, next.tri.grow(mem, next.slots), next.triOwner.grow(mem, next.slots),
        slotL, slotR);
    checkLaunch();
    scatterEventsKernel<<<blocks(events), BLOCK, 0, s>>>(
        cur.ev.data(), cur.key.data(), events32, slots32, stride32, nextStride32, split, flagScan,
        evBegin, left, right, goesScan, nextEvBegin, slotL, slotR, next.ev.grow(mem, next.events),
        next.key.grow(mem, next.events));
    checkLaunch();
    std::swap(cur, next);
    nodeBase += m;
    leafBase += leafRefs;
  }
  GVDP_CUDA_CHECK(cudaStreamSynchronize(s));
  ph.downloadMs = msSince(start) - ph.rootMs - ph.levelsMs;
  if (phases) *phases = ph;
  return tree;
}

}  // namespace gvdp::detail
