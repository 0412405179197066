// gvdp's public API (docs/DESIGN.md "Public API"): a Renderer walks a world frame by frame, in
// bounded memory, with one of the schedulers on either backend. Make one with makeRenderer:
// from a built-in scene's name (here), or from your own producer type (gvdp/make_renderer.h).
//
//   gvdp::RendererOptions o;                    // CPU, sp, 160x100 unless told otherwise
//   o.scheduler.backend = gvdp::Backend::Cuda;  // and .kind, .poolBricks, .timeline
//   auto renderer = gvdp::makeRenderer("perlin", o);
//   gvdp::Image image;
//   gvdp::FrameStats stats = renderer->render(pose, image);
#pragma once

#include <cstdint>
#include <memory>
#include <string_view>

#include "gvdp/base/camera.h"
#include "gvdp/base/error.h"  // Error, InputError
#include "gvdp/base/image.h"
#include "gvdp/sched/scheduler.h"
#include "gvdp/tiles/tiled_frame.h"

struct CUstream_st;  // cudaStream_t is CUstream_st*

namespace gvdp {

// The vocabulary of the API; everything else of the library is in gvdp::detail.
using detail::Backend;
using detail::backendName;
using detail::CacheStats;
using detail::CameraPose;
using detail::DEFAULT_FOV_DEGREES;
using detail::DEFAULT_LEVELS;
using detail::FrameSetup;
using detail::FrameStats;
using detail::Image;
using detail::MemoryReport;
using detail::parseBackend;
using detail::parseScheduler;
using detail::ProducerKernelsPtr;
using detail::psnr;
using detail::SchedulerKind;
using detail::schedulerName;
using detail::SchedulerOptions;
using detail::TileOptions;
using detail::TileProgress;

struct RendererOptions {
  SchedulerOptions scheduler;  // backend, scheduler, pool size, dp's pending launches, timeline
  int width = 160, height = 100;
  int levels = DEFAULT_LEVELS;  // clipmap levels: the voxel size doubles per level
  float fovDegrees = DEFAULT_FOV_DEGREES;
  // The image width whose pixel footprint picks the levels (0: the image's, up to
  // MAX_LOD_WIDTH, render/frame.h: wider images sample coarser levels, several rays per voxel).
  int lodWidth = 0;
  // Tiled frames (tiles/tiled_frame.h): auto by default, so that a frame whose bricks do not fit
  // the pool is rendered exactly, tile by tile, and one of any size in bounded ray memory.
  TileOptions tiles;
};

// Throws InputError naming the first bad value.
void validate(const RendererOptions& options);

// The frame a renderer with these options renders of `pose` as frame number `frameIndex`, for a
// world of finest voxel size `voxelSize0` (for code that drives a Scheduler itself).
FrameSetup frameOf(const RendererOptions& options, float voxelSize0, const CameraPose& pose,
                   int frameIndex);

class Renderer {
 public:
  // Use makeRenderer. Throws InputError for bad options or an unavailable backend.
  Renderer(const RendererOptions& options, ProducerKernelsPtr producer);
  ~Renderer();

  // The options as used: every default resolved (pool size, pending launches).
  const RendererOptions& options() const { return options_; }
  // The world's finest voxel size.
  float voxelSize0() const { return voxelSize0_; }

  // Renders the next frame of the sequence from `pose` into a host image (resized to fit), as
  // tiles where options().tiles says.
  FrameStats render(const CameraPose& pose, Image& out);
  // The same into `devicePixels` (width * height RGBA8 words of device memory), the copy
  // enqueued on `stream` (cuda backend), in one tile (a frame that overflows the pool degrades).
  // The renderer works on a stream of its own and has finished the frame when this returns; its
  // next frame waits for the copy.
  FrameStats render(const CameraPose& pose, uint32_t* devicePixels, CUstream_st* stream);
  // Called after each tile of a tiled frame (a progress bar for large stills).
  void onTile(TileProgress progress) { tileProgress_ = std::move(progress); }
  // Records the GPU-cores timeline (profile/) of the following frames into
  // FrameStats::timeline, until called again with false.
  void recordTimeline(bool on);
  // Bytes of every structure the renderer holds, by name.
  MemoryReport memory() const;
  // Frames rendered so far.
  int frames() const { return frames_; }

 private:
  FrameSetup frameAt(const CameraPose& pose) const;

  RendererOptions options_;
  float voxelSize0_;
  std::unique_ptr<detail::Scheduler> scheduler_;
  TileProgress tileProgress_;
  detail::TileMemory tileMemory_;  // the tiles the last frames kept
  int frames_ = 0;
};

// A renderer of a built-in scene ("perlin", "fbm", "forest", "random-spheres",
// "aligned-spheres"); throws InputError for an unknown name.
std::unique_ptr<Renderer> makeRenderer(std::string_view scene, const RendererOptions& options);

}  // namespace gvdp
