// Per-ray and per-brick task bodies shared by the cached schedulers (sp, graph, dp, pt) on
// both backends: the first render pass in 8x8 pixel tiles (so that a warp holds a compact
// 8x4 block), a render task resuming a saved ray, production of one brick sample, and the final
// resolve that counts unfinished pixels.
#pragma once

#include "gvdp/base/bits.h"
#include "gvdp/cache/cached_access.h"
#include "gvdp/cache/produce.h"
#include "gvdp/render/frame.h"
#include "gvdp/render/shade.h"

namespace gvdp::detail {

constexpr int TILE = 8;

GVDP_HD GVDP_INLINE int tileCount(const FrameSetup& f) {
  return ((f.width + TILE - 1) / TILE) * ((f.height + TILE - 1) / TILE);
}

// Pixel of item i of the tiled first pass, or -1 outside the image (partial edge tiles).
GVDP_HD GVDP_INLINE int tiledPixel(const FrameSetup& f, int i) {
  int tilesX = (f.width + TILE - 1) / TILE;
  int tile = i / (TILE * TILE), inTile = i % (TILE * TILE);
  int x = (tile % tilesX) * TILE + inTile % TILE;
  int y = (tile / tilesX) * TILE + inTile / TILE;
  return x < f.width && y < f.height ? y * f.width + x : -1;
}

// Ray payloads are written and read by different blocks (dp, pt): on the GPU they bypass the
// incoherent L1 (volatile accesses go to L2).
GVDP_HD GVDP_INLINE RayState loadRayState(const RayState* p) {
#if GVDP_IS_GPU_CODE
  const volatile RayState* v = p;
  return {{v->colour.x, v->colour.y, v->colour.z, v->colour.w}, v->level, v->step};
#else
  return *p;
#endif
}

GVDP_HD GVDP_INLINE void storeRayState(RayState* p, const RayState& s) {
#if GVDP_IS_GPU_CODE
  volatile RayState* v = p;
  v->colour.x = s.colour.x;
  v->colour.y = s.colour.y;
  v->colour.z = s.colour.z;
  v->colour.w = s.colour.w;
  v->level = s.level;
  v->step = s.step;
#else
  *p = s;
#endif
}

// How renderRay marches: its one ray on the thread (the CPU's sp loop), or a warp's rays together,
// their samples shared out (ray_tasks_warp.cuh: WarpRays).
struct OneRay {
  template <class Access>
  GVDP_HD MarchResult operator()(const Ray& ray, const Lod& lod, RayState& s, Access& access,
                                 bool active) const {
    return active ? march(ray, lod, s, access) : MarchResult::Finished;
  }
};

// Where renderRay leaves the rays that finish: their pixels, resolved (resolvePixel, as the
// resolve pass would from the payload), and their count. sp has no resolve pass: a frame's image
// is written as its rays finish, and its unfinished pixels are its pixels less `count` (read after
// the frame's clock). dp, pt and graph resolve every pixel from the payloads (dp's sweep and
// graph's kernels and host fallback pass none: null, and every ray's state is saved). With an
// image, only the rays still to march save their state.
struct FinishedRays {
  Rgba8* image = nullptr;
  uint32_t* count = nullptr;
};

// Adds the rays finished here to `count`: on the GPU one atomic per warp (the lanes here together).
GVDP_HD GVDP_INLINE void countFinished(uint32_t* count, bool finished) {
#if GVDP_IS_GPU_CODE
  unsigned mask = __ballot_sync(__activemask(), finished);
  if (mask && (threadIdx.x & 31u) == static_cast<unsigned>(lowestBit(mask)))
    atomicAdd(count, static_cast<uint32_t>(__popc(mask)));
#else
  if (finished) atomicAdd32(count, 1u);
#endif
}

// Algorithm 1 for one ray from its saved state, or from the eye when `fresh` (a frame's first
// pass: no state saved yet); pixel < 0: none, for a lane of a warp that has none. True when it
// stopped on a missing brick (its state is saved and it must be relaunched after production). A
// ray that finishes writes its pixel to `finished` if it has an image (else its state is saved
// for the resolve). Used by sp and graph, whose render kernels run while no brick is published:
// the pool is read-only to them.
template <class Pool, class Marches = OneRay>
GVDP_HD GVDP_INLINE bool renderRay(const FrameSetup& f, const CacheView& cache, const Pool& pool,
                                   RayState* payload, int pixel, bool fresh, FinishedRays finished,
                                   Marches marches = {}) {
  bool active = pixel >= 0;
  Ray ray = f.primaryRay(active ? pixel % f.width : 0, active ? pixel / f.width : 0);
  RayState s = active && !fresh ? payload[pixel] : initialRayState();
  CachedAccess<Pool, QueueRequest, PoolReads::ReadOnly> access{cache, pool, f.lod};
  bool stopped = marches(ray, f.lod, s, access, active) == MarchResult::Stopped;
  access.addCounts(active ? pixel : -1);
  if (stopped) noteRayStop(cache, pixel);
  bool done = active && s.finished(f.lod);
  if (finished.image) {
    if (done) finished.image[pixel] = resolvePixel(s.colour, ray.d);
    countFinished(finished.count, done);
  }
  if (active && !(done && finished.image)) payload[pixel] = s;  // the rays still to march
  return stopped;
}

GVDP_HD GVDP_INLINE Rgba8 resolveRay(const FrameSetup& f, const RayState* payload, int pixel,
                                     bool* unfinished) {
  Ray ray = f.primaryRay(pixel % f.width, pixel / f.width);
  *unfinished = !payload[pixel].finished(f.lod);
  return resolvePixel(payload[pixel].colour, ray.d);
}

}  // namespace gvdp::detail
