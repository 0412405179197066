// Seed 004's level-by-level kd-tree builder on the GPU (kdtree_build.h buildKdTreeCuda): the
// steps of kdtree_parallel.cpp, one CUB call or one element-wise kernel each, over the same flat
// arrays (a level's nodes, its slots, its events per axis), the rules being kdtree.h's GVDP_HD
// functions. Nodes and leaf triangles are written in the same places as the parallel builder's,
// so the two trees are equal even in storage. On the device: the triangles' boxes (from the
// uploaded vertices and indices), the root box (cub::DeviceReduce), the root events (counted,
// cub::DeviceScan, written in triangle order, then a stable cub::DeviceRadixSort on eventKey:
// kdEventLess's order) and every level. The host only reads back each level's totals (to size
// the next arrays) and its nodes and leaf triangles. Built with --fmad=false (src/CMakeLists.txt)
// on top of the explicitly rounded operations of base/rounded_math.h.
#include <cuda_runtime.h>

#include <array>
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_reduce.cuh>
#include <cub/device/device_scan.cuh>
#include <cub/device/device_segmented_reduce.cuh>

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

__global__ void eventCountsKernel(const KdEvent* ev, uint32_t n, KdEventCounts* counts) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n) counts[i] = countsOf(ev[i]);
}

// (1) every event's candidate (evaluateEvent), with its node's counts before it.
__global__ void evaluateEventsKernel(const KdEvent* ev, uint32_t n, const uint32_t* evOwner,
                                     const uint32_t* evBegin, const KdEventCounts* before,
                                     const uint32_t* triBegin, const Box3f* box, int axis,
                                     KdSplit* out) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  uint32_t j = evOwner[i], b = evBegin[j];
  out[i] = evaluateEvent(ev, i, b, evBegin[j + 1], before[i] - before[b],
                         triBegin[j + 1] - triBegin[j], box[j], axis);
}

__global__ void mergeBestKernel(const KdSplit* axisBest, uint32_t m, bool first, KdSplit* best) {
  uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j >= m) return;
  if (first || betterSplit(axisBest[j], best[j])) best[j] = axisBest[j];
}

// (2) the leaf rule; split[m] = leafTris[m] = 0 (the scans' totals land there).
__global__ void decideKernel(const Box3f* box, const uint32_t* triBegin, const KdSplit* best,
                             uint32_t m, int depth, uint32_t* split, uint32_t* leafTris) {
  uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j > m) return;
  if (j == m) {
    split[m] = leafTris[m] = 0;
    return;
  }
  uint32_t n = triBegin[j + 1] - triBegin[j];
  bool s = shouldSplit(box[j], n, depth, best[j]);
  split[j] = s;
  leafTris[j] = s ? 0u : n;
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
// (slotOf: the events, whose triangle field is their slot); goesL[n] = goesR[n] = 0 ...
__global__ void goesKernel(const KdEvent* slotOf, uint32_t n, const uint32_t* triOwner,
                           const uint32_t* split, const uint8_t* left, const uint8_t* right,
                           uint32_t* goesL, uint32_t* goesR) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i > n) return;
  if (i == n) {
    goesL[n] = goesR[n] = 0;
    return;
  }
  uint32_t slot = slotOf ? eventTriangle(slotOf[i]) : i;
  bool s = split[triOwner[slot]] != 0;
  goesL[i] = s && left[slot];
  goesR[i] = s && right[slot];
}

// ... the children's element counts in child order (from the scans of those flags) ...
__global__ void childCountsKernel(const uint32_t* split, const uint32_t* rank,
                                  const uint32_t* begin, const uint32_t* scanL,
                                  const uint32_t* scanR, uint32_t m, uint32_t* childCount) {
  uint32_t j = blockIdx.x * blockDim.x + threadIdx.x;
  if (j >= m || !split[j]) return;
  childCount[2 * rank[j]] = scanL[begin[j + 1]] - scanL[begin[j]];
  childCount[2 * rank[j] + 1] = scanR[begin[j + 1]] - scanR[begin[j]];
}

// ... the slots placed in their children's segments, order kept ...
__global__ void scatterSlotsKernel(const uint32_t* tri, const uint32_t* triOwner, uint32_t slots,
                                   const uint32_t* split, const uint32_t* rank,
                                   const uint32_t* triBegin, const uint8_t* left,
                                   const uint8_t* right, const uint32_t* scanL,
                                   const uint32_t* scanR, const uint32_t* nextBegin,
                                   uint32_t* nextTri, uint32_t* nextOwner, uint32_t* slotL,
                                   uint32_t* slotR) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= slots) return;
  uint32_t j = triOwner[i];
  if (!split[j]) return;
  uint32_t b = triBegin[j], c = 2 * rank[j];
  if (left[i]) {
    uint32_t dst = nextBegin[c] + scanL[i] - scanL[b];
    nextTri[dst] = tri[i];
    nextOwner[dst] = c;
    slotL[i] = dst;
  }
  if (right[i]) {
    uint32_t dst = nextBegin[c + 1] + scanR[i] - scanR[b];
    nextTri[dst] = tri[i];
    nextOwner[dst] = c + 1;
    slotR[i] = dst;
  }
}

// ... and the events likewise, renamed to their slots in the children.
__global__ void scatterEventsKernel(const KdEvent* ev, uint32_t n, const uint32_t* evOwner,
                                    const uint32_t* split, const uint32_t* rank,
                                    const uint32_t* evBegin, const uint8_t* left,
                                    const uint8_t* right, const uint32_t* scanL,
                                    const uint32_t* scanR, const uint32_t* nextBegin,
                                    const uint32_t* slotL, const uint32_t* slotR, KdEvent* nextEv,
                                    uint32_t* nextOwner) {
  uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n) return;
  uint32_t j = evOwner[i];
  if (!split[j]) return;
  KdEvent e = ev[i];
  uint32_t slot = eventTriangle(e), c = 2 * rank[j];
  if (left[slot]) {
    uint32_t dst = nextBegin[c] + scanL[i] - scanL[evBegin[j]];
    nextEv[dst] = {e.pos, slotL[slot] << 2 | eventType(e)};
    nextOwner[dst] = c;
  }
  if (right[slot]) {
    uint32_t dst = nextBegin[c + 1] + scanR[i] - scanR[evBegin[j]];
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

// A grow-only device array: at least n elements (contents kept only when no growth). The old
// array is freed after the device's queued work (which may still use it) is done.
template <class T>
T* grow(DeviceBuffer<T>& b, uint64_t n) {
  if (b.size() >= n) return b.data();
  if (b.data()) GVDP_CUDA_CHECK(cudaDeviceSynchronize());
  b = DeviceBuffer<T>(n + n / 4 + 64);
  return b.data();
}

// CUB's two-call pattern on one grow-only temporary buffer: call(temp, bytes) sizes, then runs.
struct Cub {
  cudaStream_t stream;
  DeviceBuffer<uint8_t> temp;

  template <class Call>
  void operator()(Call call) {
    size_t bytes = 0;
    GVDP_CUDA_CHECK(call(nullptr, bytes));
    void* t = grow(temp, bytes > 0 ? bytes : 1);
    GVDP_CUDA_CHECK(call(t, bytes));
  }
  // out[i] = in[0] + ... + in[i - 1], over n elements (in[n - 1] is 0 where the total is wanted).
  void exclusiveSum(const uint32_t* in, uint32_t* out, uint64_t n) {
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
  DeviceBuffer<Box3f> box;
  DeviceBuffer<uint32_t> triBegin;                // nodes + 1
  std::array<DeviceBuffer<uint32_t>, 3> evBegin;  // nodes + 1 per axis
  DeviceBuffer<uint32_t> tri, triOwner;           // per slot
  std::array<DeviceBuffer<KdEvent>, 3> ev;        // triangleAndType: slot << 2 | type
  std::array<DeviceBuffer<uint32_t>, 3> evOwner;  // per event
  uint64_t nodes = 0, slots = 0;
  std::array<uint64_t, 3> events{};
};

// Scratch arrays of a level (grow-only, kept across levels).
struct Scratch {
  DeviceBuffer<KdEventCounts> counts, before;
  DeviceBuffer<KdSplit> evaluated, axisBest, best;
  DeviceBuffer<uint32_t> split, rank, leafTris, leafOffset;
  DeviceBuffer<uint8_t> left, right;
  DeviceBuffer<uint32_t> goesL, goesR, scanL, scanR, slotL, slotR, childCount;
  DeviceBuffer<KdNode> nodes;
  DeviceBuffer<uint32_t> leafTriangles;
};

void checkSize(uint64_t n) {
  GVDP_CHECK(n < (uint64_t{1} << 31) - 1, "kd-tree (GPU): ", n, " elements in one array");
}

// The root level: one node, slot t = triangle t, each axis's events sorted (kdRootEvents).
void rootLevel(const Mesh& mesh, DeviceLevel& l, Box3f& bounds, Cub& cub) {
  cudaStream_t s = cub.stream;
  auto n = static_cast<uint32_t>(mesh.triangleCount());
  checkSize(2 * uint64_t{n} + 1);
  DeviceBuffer<Vec3f> vertices(mesh.vertices.size());
  DeviceBuffer<uint32_t> indices(mesh.indices.size());
  writeDevice(vertices.data(), mesh.vertices.data(), vertices.bytes(), s);
  writeDevice(indices.data(), mesh.indices.data(), indices.bytes(), s);
  DeviceBuffer<Box3f> boxes(n), root(1);
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
  writeDevice(grow(l.box, 1), &bounds, sizeof bounds, s);
  const uint32_t triBegin[2] = {0, n};
  writeDevice(grow(l.triBegin, 2), triBegin, sizeof triBegin, s);
  iotaKernel<<<blocks(n), BLOCK, 0, s>>>(grow(l.tri, n), n);
  checkLaunch();
  fillDevice(grow(l.triOwner, n), 0, n * sizeof(uint32_t), s);

  DeviceBuffer<uint32_t> count(n + 1), offset(n + 1);
  DeviceBuffer<KdEvent> unsorted(2 * uint64_t{n});
  DeviceBuffer<uint64_t> keys(2 * uint64_t{n}), sortedKeys(2 * uint64_t{n});
  DeviceBuffer<uint32_t> index(2 * uint64_t{n}), sortedIndex(2 * uint64_t{n});
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
                                                        grow(l.ev[axis], events));
    checkLaunch();
    const uint32_t evBegin[2] = {0, events};
    writeDevice(grow(l.evBegin[axis], 2), evBegin, sizeof evBegin, s);
    fillDevice(grow(l.evOwner[axis], events), 0, events * sizeof(uint32_t), s);
    l.events[axis] = events;
  }
  // the temporaries above are freed on return: cudaFree waits for the work using them
}

}  // namespace

KdTree buildKdTreeCuda(const Mesh& mesh) {
  OwnedGpuStream owned(createGpuStream());
  auto s = static_cast<cudaStream_t>(owned.get());
  Cub cub{s, {}};
  KdTree tree;
  if (mesh.triangleCount() == 0) {  // the root is an empty leaf (as the CPU builders make it)
    tree.nodes = {kdLeaf(0, 0)};
    return tree;
  }
  DeviceLevel cur, next;
  Scratch x;
  rootLevel(mesh, cur, tree.bounds, cub);
  uint32_t nodeBase = 0;
  for (int depth = 0; cur.nodes > 0; ++depth) {
    const uint64_t m = cur.nodes;
    const auto m32 = static_cast<uint32_t>(m);
    checkSize(m + 1);
    KdSplit* best = grow(x.best, m);

    // (1) the best split of every node: per axis, a scan of the event counts, every event
    // evaluated, a segmented reduction per node (betterSplit), merged over the axes
    for (int axis = 0; axis < 3; ++axis) {
      const uint64_t n = cur.events[axis];
      checkSize(n);
      const auto n32 = static_cast<uint32_t>(n);
      KdEventCounts* counts = grow(x.counts, n);
      KdEventCounts* before = grow(x.before, n);
      KdSplit* evaluated = grow(x.evaluated, n);
      KdSplit* axisBest = grow(x.axisBest, m);
      const uint32_t* evBegin = cur.evBegin[axis].data();
      eventCountsKernel<<<blocks(n), BLOCK, 0, s>>>(cur.ev[axis].data(), n32, counts);
      checkLaunch();
      cub([&](void* t, size_t& b) {
        return cub::DeviceScan::ExclusiveScan(t, b, counts, before, AddCounts{},
                                              KdEventCounts{0, 0, 0}, static_cast<int>(n), s);
      });
      evaluateEventsKernel<<<blocks(n), BLOCK, 0, s>>>(
          cur.ev[axis].data(), n32, cur.evOwner[axis].data(), evBegin, before, cur.triBegin.data(),
          cur.box.data(), axis, evaluated);
      checkLaunch();
      cub([&](void* t, size_t& b) {
        return cub::DeviceSegmentedReduce::Reduce(t, b, evaluated, axisBest, static_cast<int>(m),
                                                  evBegin, evBegin + 1, BestOf{}, noSplit(), s);
      });
      mergeBestKernel<<<blocks(m), BLOCK, 0, s>>>(axisBest, m32, axis == 0, best);
      checkLaunch();
    }

    // (2) which nodes split; ranks among the split nodes, leaf triangle offsets; their totals
    uint32_t* split = grow(x.split, m + 1);
    uint32_t* rank = grow(x.rank, m + 1);
    uint32_t* leafTris = grow(x.leafTris, m + 1);
    uint32_t* leafOffset = grow(x.leafOffset, m + 1);
    decideKernel<<<blocks(m + 1), BLOCK, 0, s>>>(cur.box.data(), cur.triBegin.data(), best, m32,
                                                 depth, split, leafTris);
    checkLaunch();
    cub.exclusiveSum(split, rank, m + 1);
    cub.exclusiveSum(leafTris, leafOffset, m + 1);
    const uint32_t splits = readValue(rank + m, s);
    const uint32_t leafRefs = readValue(leafOffset + m, s);

    // (3) the sides of every slot of a split node
    const uint64_t slots = cur.slots;
    const auto slots32 = static_cast<uint32_t>(slots);
    uint8_t* left = grow(x.left, slots);
    uint8_t* right = grow(x.right, slots);
    fillDevice(left, 0, slots, s);
    fillDevice(right, 0, slots, s);
    for (int axis = 0; axis < 3; ++axis) {
      const uint64_t n = cur.events[axis];
      sidesKernel<<<blocks(n), BLOCK, 0, s>>>(cur.ev[axis].data(), static_cast<uint32_t>(n),
                                              cur.evOwner[axis].data(), split, best, axis, left,
                                              right);
      checkLaunch();
    }

    // (4) the level's nodes and leaves out
    const uint32_t nextBase = nodeBase + m32;
    const auto leafBase = static_cast<uint32_t>(tree.leafTriangles.size());
    GVDP_CHECK(uint64_t{nextBase} + 2 * uint64_t{splits} <= KD_MAX_INDEX &&
                   uint64_t{leafBase} + leafRefs <= KD_MAX_INDEX,
               "kd-tree past 2^30 nodes or leaf references");
    KdNode* nodes = grow(x.nodes, m);
    uint32_t* leafTriangles = grow(x.leafTriangles, leafRefs);
    nodesKernel<<<blocks(m), BLOCK, 0, s>>>(split, best, rank, leafOffset, cur.triBegin.data(), m32,
                                            nextBase, leafBase, nodes);
    checkLaunch();
    leafTrianglesKernel<<<blocks(slots), BLOCK, 0, s>>>(cur.tri.data(), cur.triOwner.data(),
                                                        slots32, split, cur.triBegin.data(),
                                                        leafOffset, leafTriangles);
    checkLaunch();
    tree.nodes.resize(nextBase + 2 * size_t{splits});
    tree.leafTriangles.resize(leafBase + size_t{leafRefs});
    readDevice(tree.nodes.data() + nodeBase, nodes, m * sizeof(KdNode), s);
    if (leafRefs > 0)
      readDevice(tree.leafTriangles.data() + leafBase, leafTriangles, leafRefs * sizeof(uint32_t),
                 s);
    if (splits == 0) break;

    // (5) the next level: boxes; slots, then events, placed by scans of their side flags
    const uint64_t children = 2 * uint64_t{splits};
    checkSize(children + 1);
    next.nodes = children;
    childBoxesKernel<<<blocks(m), BLOCK, 0, s>>>(cur.box.data(), split, best, rank, m32,
                                                 grow(next.box, children));
    checkLaunch();
    uint32_t* childCount = grow(x.childCount, children + 1);
    fillDevice(childCount + children, 0, sizeof(uint32_t), s);
    uint32_t* goesL = grow(x.goesL, slots + 1);
    uint32_t* goesR = grow(x.goesR, slots + 1);
    uint32_t* scanL = grow(x.scanL, slots + 1);
    uint32_t* scanR = grow(x.scanR, slots + 1);
    goesKernel<<<blocks(slots + 1), BLOCK, 0, s>>>(nullptr, slots32, cur.triOwner.data(), split,
                                                   left, right, goesL, goesR);
    checkLaunch();
    cub.exclusiveSum(goesL, scanL, slots + 1);
    cub.exclusiveSum(goesR, scanR, slots + 1);
    childCountsKernel<<<blocks(m), BLOCK, 0, s>>>(split, rank, cur.triBegin.data(), scanL, scanR,
                                                  m32, childCount);
    checkLaunch();
    uint32_t* nextTriBegin = grow(next.triBegin, children + 1);
    cub.exclusiveSum(childCount, nextTriBegin, children + 1);
    next.slots = readValue(nextTriBegin + children, s);
    checkSize(next.slots);
    GVDP_CHECK(next.slots <= KD_MAX_INDEX, "kd-tree (GPU): past 2^30 slots in one level");
    uint32_t* slotL = grow(x.slotL, slots);
    uint32_t* slotR = grow(x.slotR, slots);
    scatterSlotsKernel<<<blocks(slots), BLOCK, 0, s>>>(
        cur.tri.data(), cur.triOwner.data(), slots32, split, rank, cur.triBegin.data(), left, right,
        scanL, scanR, nextTriBegin, grow(next.tri, next.slots), grow(next.triOwner, next.slots),
        slotL, slotR);
    checkLaunch();
    for (int axis = 0; axis < 3; ++axis) {
      const uint64_t n = cur.events[axis];
      const auto n32 = static_cast<uint32_t>(n);
      const KdEvent* ev = cur.ev[axis].data();
      // the slot scans are done with: goes/scan arrays are reused for the events
      uint32_t* evGoesL = grow(x.goesL, n + 1);
      uint32_t* evGoesR = grow(x.goesR, n + 1);
      uint32_t* evScanL = grow(x.scanL, n + 1);
      uint32_t* evScanR = grow(x.scanR, n + 1);
      goesKernel<<<blocks(n + 1), BLOCK, 0, s>>>(ev, n32, cur.triOwner.data(), split, left, right,
                                                 evGoesL, evGoesR);
      checkLaunch();
      cub.exclusiveSum(evGoesL, evScanL, n + 1);
      cub.exclusiveSum(evGoesR, evScanR, n + 1);
      childCountsKernel<<<blocks(m), BLOCK, 0, s>>>(split, rank, cur.evBegin[axis].data(), evScanL,
                                                    evScanR, m32, childCount);
      checkLaunch();
      uint32_t* nextEvBegin = grow(next.evBegin[axis], children + 1);
      cub.exclusiveSum(childCount, nextEvBegin, children + 1);
      uint64_t nextEvents = readValue(nextEvBegin + children, s);
      checkSize(nextEvents);
      next.events[axis] = nextEvents;
      scatterEventsKernel<<<blocks(n), BLOCK, 0, s>>>(
          ev, n32, cur.evOwner[axis].data(), split, rank, cur.evBegin[axis].data(), left, right,
          evScanL, evScanR, nextEvBegin, slotL, slotR, grow(next.ev[axis], nextEvents),
          grow(next.evOwner[axis], nextEvents));
      checkLaunch();
    }
    std::swap(cur, next);
    nodeBase = nextBase;
  }
  GVDP_CUDA_CHECK(cudaStreamSynchronize(s));
  return tree;
}

}  // namespace gvdp::detail
