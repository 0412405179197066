#include "gvdp/renderer.h"

#include "gvdp/base/error.h"
#include "gvdp/base/gpu.h"
#include "gvdp/sched/builtin_producer.h"
#include "gvdp/sched/graph/graph.h"
#include "gvdp/sched/pt/pt.h"
#include "gvdp/world/registry.h"

namespace gvdp {

using namespace detail;

void validate(const RendererOptions& o) {
  GVDP_INPUT_CHECK(o.width >= 8 && o.width <= MAX_IMAGE_SIDE, "bad --width ", o.width,
                   " (expected 8..", MAX_IMAGE_SIDE, ")");
  GVDP_INPUT_CHECK(o.height >= 8 && o.height <= MAX_IMAGE_SIDE, "bad --height ", o.height,
                   " (expected 8..", MAX_IMAGE_SIDE, ")");
  GVDP_INPUT_CHECK(static_cast<int64_t>(o.width) * o.height <= MAX_IMAGE_PIXELS, "bad size ",
                   o.width, "x", o.height, " (at most ", MAX_IMAGE_PIXELS >> 20, " Mpixels)");
  GVDP_INPUT_CHECK(o.tiles.maxTilePixels >= 64 && o.tiles.maxTilePixels <= MAX_IMAGE_PIXELS,
                   "bad maximum tile size ", o.tiles.maxTilePixels, " pixels (expected 64..",
                   MAX_IMAGE_PIXELS, ")");
  GVDP_INPUT_CHECK(o.tiles.mode != TileOptions::Mode::Grid ||
                       (o.tiles.grid >= 1 && o.tiles.grid <= MAX_TILE_GRID),
                   "bad --tiles ", o.tiles.grid, " (expected 1..", MAX_TILE_GRID, ")");
  initialTiles(o.width, o.height, o.tiles);  // refuses a frame too large for --tiles off
  GVDP_INPUT_CHECK(o.levels >= 1 && o.levels <= MAX_LEVELS, "bad --levels ", o.levels,
                   " (expected 1..", MAX_LEVELS, ")");
  GVDP_INPUT_CHECK(o.lodWidth >= 0 && o.lodWidth <= MAX_IMAGE_SIDE, "bad --lod-width ", o.lodWidth,
                   " (expected 0..", MAX_IMAGE_SIDE, "; 0: the image's, up to ", MAX_LOD_WIDTH,
                   ")");
  GVDP_INPUT_CHECK(o.fovDegrees >= 1.0f && o.fovDegrees <= 150.0f, "bad --fov ", o.fovDegrees,
                   " (expected 1..150 degrees)");
  if (o.scheduler.kind == SchedulerKind::Graph) graphDriverFromEnvironment();
  GVDP_INPUT_CHECK(o.scheduler.farPrefetch <= MAX_FAR_PREFETCH, "bad --far-prefetch ",
                   o.scheduler.farPrefetch, " (expected 0..", MAX_FAR_PREFETCH,
                   " predicted frames; 0: off)");
  if (o.scheduler.kind == SchedulerKind::Pt) ptProducerShareFromEnvironment();
}

namespace {
RendererOptions resolved(RendererOptions o) {
  validate(o);
  o.scheduler = resolvedOptions(o.scheduler);
  return o;
}
}  // namespace

Renderer::Renderer(const RendererOptions& options, ProducerKernelsPtr producer)
    : options_(resolved(options)),
      voxelSize0_(producer->voxelSize0()),
      scheduler_(makeScheduler(options_.scheduler, std::move(producer))) {
  GVDP_INPUT_CHECK(voxelSize0_ > 0.0f && voxelSize0_ < 1e6f, "bad producer voxelSize0() ",
                   voxelSize0_, " (expected a positive size below 1e6)");
}

Renderer::~Renderer() = default;

FrameSetup frameOf(const RendererOptions& o, float voxelSize0, const CameraPose& pose,
                   int frameIndex) {
  return makeFrame(pose, voxelSize0, o.width, o.height, o.levels, frameIndex, o.fovDegrees,
                   o.lodWidth);
}

FrameSetup Renderer::frameAt(const CameraPose& pose) const {
  return frameOf(options_, voxelSize0_, pose, frames_);
}

FrameStats Renderer::render(const CameraPose& pose, Image& out) {
  FrameStats stats = renderTiled(*scheduler_, frameAt(pose), out, options_.tiles,
                                 options_.scheduler.poolBricks, tileProgress_, &tileMemory_);
  ++frames_;
  return stats;
}

FrameStats Renderer::render(const CameraPose& pose, uint32_t* devicePixels, CUstream_st* stream) {
  GVDP_INPUT_CHECK(devicePixels, "render to device memory: null pixel pointer");
  GVDP_INPUT_CHECK(
      static_cast<int64_t>(options_.width) * options_.height <= options_.tiles.maxTilePixels,
      "render to device memory: ", options_.width, "x", options_.height, " is over one tile's ",
      options_.tiles.maxTilePixels, " pixels");
  FrameStats stats = scheduler_->render(frameAt(pose), nullptr);
  ++frames_;
  // The frame is finished on the renderer's stream; the next one waits for this copy.
  copyDeviceAsync(devicePixels, scheduler_->deviceImage(),
                  static_cast<size_t>(options_.width) * options_.height * sizeof(uint32_t), stream,
                  scheduler_->stream());
  return stats;
}

void Renderer::recordTimeline(bool on) {
  recordTimelineOf(*scheduler_, options_.scheduler.backend, on);
}

MemoryReport Renderer::memory() const {
  return scheduler_->memory();
}

std::unique_ptr<Renderer> makeRenderer(std::string_view scene, const RendererOptions& options) {
  return std::make_unique<Renderer>(options, builtinProducerKernels(findScene(scene).world));
}

}  // namespace gvdp
