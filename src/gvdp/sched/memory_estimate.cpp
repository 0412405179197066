#include "gvdp/sched/memory_estimate.h"

#include "gvdp/base/gpu.h"
#include "gvdp/base/host_memory.h"
#include "gvdp/base/parallel.h"
#include "gvdp/cache/cache_view.h"
#include "gvdp/cache/clipmap.h"
#include "gvdp/cache/lru_order.h"
#include "gvdp/render/march.h"
#include "gvdp/sched/dp/dp.h"
#include "gvdp/sched/pt/pt_context.h"
#include "gvdp/sched/tile_order.h"

namespace gvdp::detail {
namespace {

// pt's worker warps on CUDA (pt_cuda.cpp: blocks x 8): about 4096 on a large GPU.
constexpr uint32_t PT_CUDA_WORKER_WARPS = 4096;

// The brick cache (brick_cache.h and its two backends' operations).
MemoryReport cacheItems(const SchedulerOptions& o, const FrameSetup& f) {
  size_t k = poolBricksOf(o), pixels = static_cast<size_t>(f.pixelCount());
  MemoryReport m = {{"brick_pool", k * BRICK_SAMPLE_COUNT * sizeof(Rgba8)},
                    {"brick_occupancy", k * sizeof(uint64_t)},
                    {"indirection_table", clipmapOf(f).entryCount() * sizeof(uint32_t)},
                    {"inverse_table", k * sizeof(BrickKey)},
                    {"timestamps", k * sizeof(uint32_t)}};
  // Two LRU orders (lru_order.h: the free slot list is the head of one, the next is built from
  // it), and on CUDA each tile's part sizes (cache_kernels.cu).
  size_t lru = 2 * k * sizeof(uint32_t);
  if (o.backend == Backend::Cuda) lru += lruTileCount(static_cast<uint32_t>(k)) * sizeof(uint64_t);
  m.push_back({"lru_order", lru});
  m.push_back({"request_queue", pixels * sizeof(BrickKey)});
  m.push_back({"box_lists", BOX_LISTS * BOX_LIST_CAPACITY * sizeof(BrickKey)});
  return m;
}

// The per-pixel structures of each scheduler on the CPU (*_cpu.cpp).
void addCpuRayItems(const SchedulerOptions& o, size_t pixels, MemoryReport& m) {
  size_t payload = pixels * sizeof(RayState), list = pixels * sizeof(uint32_t);
  uint32_t n = static_cast<uint32_t>(pixels);
  switch (o.kind) {
    case SchedulerKind::Sp:
    case SchedulerKind::Graph:
      m.push_back({"ray_payload", payload});
      m.push_back({"live_ray_lists", 2 * list});
      break;
    case SchedulerKind::Dp:
      m.push_back({"ray_payload", payload});
      m.push_back({"ray_locks", list});
      m.push_back({"task_queue", dpCpuTaskQueueBytes(pendingLaunchesOf(o))});
      m.push_back({"sweep_ray_lists", 2 * list});
      break;
    case SchedulerKind::Pt:
      m.push_back({"ray_payload", payload});
      m.push_back({"pt_queues_and_wait_lists",
                   PtLayout{n, static_cast<uint32_t>(ThreadPool::global().size())}.bytes()});
      break;
    case SchedulerKind::Direct:
      break;
  }
}

// The same on CUDA (SpBuffersCuda: payload, two live lists and the image; *_cuda.cpp).
void addCudaRayItems(const SchedulerOptions& o, const FrameSetup& f, MemoryReport& m) {
  size_t pixels = static_cast<size_t>(f.pixelCount());
  if (o.kind == SchedulerKind::Direct) {
    m.push_back({"device_image", pixels * sizeof(uint32_t)});
    return;
  }
  m.push_back({"ray_payload_lists_image", pixels * (sizeof(RayState) + 3 * sizeof(uint32_t))});
  uint32_t n = static_cast<uint32_t>(pixels);
  if (o.kind == SchedulerKind::Dp) m.push_back({"ray_locks", pixels * sizeof(uint32_t)});
  if (o.kind == SchedulerKind::Pt)
    m.push_back({"pt_queues_and_wait_lists", PtLayout{n, PT_CUDA_WORKER_WARPS}.bytes()});
  if (o.kind == SchedulerKind::Sp || o.kind == SchedulerKind::Pt)  // 2 costs, keys, order
    m.push_back({"tile_order", size_t{4} * orderBlockCount(f) * sizeof(uint32_t)});
}

}  // namespace

MemoryReport memoryEstimate(const SchedulerOptions& o, const FrameSetup& f) {
  size_t pixels = static_cast<size_t>(f.pixelCount());
  MemoryReport m;
  if (o.kind != SchedulerKind::Direct) m = cacheItems(o, f);
  if (o.backend == Backend::Cuda) {
    addCudaRayItems(o, f, m);
  } else {
    addCpuRayItems(o, pixels, m);
    m.push_back({"image", pixels * sizeof(uint32_t)});  // the image every frame lands in
  }
  return m;
}

uint64_t memoryTotal(const MemoryReport& report) {
  uint64_t total = 0;
  for (const MemoryItem& item : report) total += item.bytes;
  return total;
}

std::optional<uint64_t> backendMemoryBytes(Backend backend) {
  return backend == Backend::Cuda ? cudaFreeMemoryBytes() : hostAvailableMemoryBytes();
}

}  // namespace gvdp::detail
