// The paper's scheduler (3.3, Algorithms 1 and 2) as one protocol for both backends: render
// tasks cover the screen in 32x16-pixel tiles; a render thread that wins the CAS on a MISSING
// brick launches its production; a finished production relaunches the rays of the brick's
// screen-space bounding box, each thread trying its ray's lock. On the GPU a launch is a CDP2
// fire-and-forget grid; on the CPU it pushes a task to a queue.
//
// Race-free relaunch (docs/DESIGN.md, fixing paper 3.3.3): a ray that stops releases its lock, then
// re-reads the entry it stopped on; if the brick was published meanwhile, it takes its lock back
// and goes on. Either the relaunch or the ray itself then holds the lock: no ray is lost.
#pragma once

#include "gvdp/cache/cached_access.h"
#include "gvdp/sched/ray_tasks.h"

namespace gvdp::detail {

constexpr uint32_t RAY_FREE = 0, RAY_HELD = 1, RAY_DONE = 2;
constexpr int DP_TILE_W = 32, DP_TILE_H = 16;

enum DpCounter : int {
  DP_PRODUCTIONS,      // production launches
  DP_RELAUNCHES,       // render relaunches
  DP_LAUNCH_FAILURES,  // launches refused: past the frame's allowance or by the runtime (GPU),
                       // the task queue full (CPU)
  DP_DEFERRED,         // productions left to the host sweep (launch depth limit)
  DP_RESERVED,         // GPU: device launches reserved from the frame's allowance (dp_kernels.cuh)
  DP_COUNTER_COUNT
};

struct PixelRect {
  int x0, y0, x1, y1;  // [x0, x1) x [y0, y1)
  GVDP_HD int width() const { return x1 - x0; }
  GVDP_HD int height() const { return y1 - y0; }
};

struct DpContext {
  FrameSetup frame;
  CacheView cache;
  RayState* payload;
  uint32_t* locks;     // per pixel: RAY_FREE, RAY_HELD or RAY_DONE
  uint32_t* counters;  // DpCounter
  BrickPool pool;
  uint32_t launchAllowance;  // GPU: the device launches a frame may make (dp_kernels.cuh)
};

// Pixels whose centre ray may cross the brick (paper 3.3.2): the projected corners' bounds,
// widened by a pixel, in the image, then in the frame's tile; the whole tile when the brick
// reaches behind the eye.
GVDP_HD GVDP_INLINE PixelRect brickScreenRect(const FrameSetup& f, const Clipmap& clipmap,
                                              const BrickKey& key) {
  PixelRect full{0, 0, f.width, f.height};
  float side = f.lod.voxelSize(key.level) * BRICK_WIDTH;
  Vec3i local = key.brick - clipmap.localOriginBrick[key.level];
  Vec3f lo{local.x * side, local.y * side, local.z * side};
  float w = static_cast<float>(f.imageWidth), h = static_cast<float>(f.imageHeight);
  float aspect = h / w;
  float minX = 1e30f, minY = 1e30f, maxX = -1e30f, maxY = -1e30f;
  for (int c = 0; c < 8; ++c) {
    Vec3f corner = lo + Vec3f{(c & 1) * side, ((c >> 1) & 1) * side, (c >> 2) * side} - f.eye;
    float z = dot(corner, f.basis.forward);
    if (z <= 1e-3f * side) return full;
    float sx = dot(corner, f.basis.right) / (z * f.tanHalfFov);
    float sy = dot(corner, f.basis.up) / (z * f.tanHalfFov * aspect);
    float px = (sx + 1.0f) * 0.5f * w, py = (1.0f - sy) * 0.5f * h;
    minX = fminf(minX, px);
    maxX = fmaxf(maxX, px);
    minY = fminf(minY, py);
    maxY = fmaxf(maxY, py);
  }
  PixelRect r{
      static_cast<int>(floorf(minX)) - 1 - f.tileX, static_cast<int>(floorf(minY)) - 1 - f.tileY,
      static_cast<int>(ceilf(maxX)) + 1 - f.tileX, static_cast<int>(ceilf(maxY)) + 1 - f.tileY};
  r.x0 = r.x0 < 0 ? 0 : r.x0;
  r.y0 = r.y0 < 0 ? 0 : r.y0;
  r.x1 = r.x1 > f.width ? f.width : r.x1;
  r.y1 = r.y1 > f.height ? f.height : r.y1;
  return r;
}

// The CAS winner's action: launch the brick's production (Launcher::produce). A claim past a
// budgeted frame's deadline (no ray waits for it) is queued instead, for the sweep at the frame's
// end: launched, it would relaunch its brick's rays for nothing, and one ray past the deadline
// claims every missing brick on its path. Launched from the render threads, those claims hung 9
// of 15 cold 96x64 runs at budget 0 on an H100; queued, 15 of 15 finished. That was before the
// frame's launch allowance (dp_kernels.cuh), likely the same hang (the runtime refusing
// launches), not run again since.
template <class Launcher>
struct LaunchProduction {
  Launcher* launcher;
  GVDP_HD void operator()(const CacheView&, int level, Vec3i g, uint32_t* entry) const {
    if (claimBrick(entry)) launcher->produce(BrickKey{g, level}, entry);
  }
  GVDP_HD void ahead(const CacheView& cache, int level, Vec3i g, uint32_t* entry) const {
    QueueRequest{}(cache, level, g, entry);
  }
};

// Algorithm 1 with the lock protocol, for one pixel of a render task.
template <class Pool, class Launcher>
GVDP_HD void dpRenderPixel(const DpContext& ctx, const Pool& pool, Launcher& launcher, int pixel) {
  uint32_t* lock = &ctx.locks[pixel];
  if (atomicCas32(lock, RAY_FREE, RAY_HELD) != RAY_FREE) return;  // alive elsewhere, or done
  const FrameSetup& f = ctx.frame;
  Ray ray = f.primaryRay(pixel % f.width, pixel / f.width);
  for (;;) {
    RayState s = loadRayState(&ctx.payload[pixel]);
    CachedAccess<Pool, LaunchProduction<Launcher>> access{ctx.cache, pool, f.lod,
                                                          LaunchProduction<Launcher>{&launcher}};
    MarchResult r = march(ray, f.lod, s, access);
    access.addCounts(pixel);
    storeRayState(&ctx.payload[pixel], s);
    if (r == MarchResult::Finished) {
      storeRelease32(lock, RAY_DONE);
      return;
    }
    noteRayStop(ctx.cache, pixel);
    storeRelease32(lock, RAY_FREE);
    fenceSeqCst();
    uint32_t e = loadAcquire32(access.stopEntry);
    if (e == ENTRY_MISSING || e == ENTRY_IN_PRODUCTION) return;     // its relaunch will come
    if (atomicCas32(lock, RAY_FREE, RAY_HELD) != RAY_FREE) return;  // the relaunch has it
  }
}

// Pixel of thread i of root task `tile` (32x16 tiles, row-major), or -1 outside the image.
GVDP_HD GVDP_INLINE int dpTilePixel(const FrameSetup& f, int tile, int i) {
  int tilesX = (f.width + DP_TILE_W - 1) / DP_TILE_W;
  int x = (tile % tilesX) * DP_TILE_W + i % DP_TILE_W;
  int y = (tile / tilesX) * DP_TILE_H + i / DP_TILE_W;
  return x < f.width && y < f.height ? y * f.width + x : -1;
}

GVDP_HD GVDP_INLINE int dpTileCount(const FrameSetup& f) {
  return ((f.width + DP_TILE_W - 1) / DP_TILE_W) * ((f.height + DP_TILE_H - 1) / DP_TILE_H);
}

}  // namespace gvdp::detail
