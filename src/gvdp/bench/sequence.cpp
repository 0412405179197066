#include "gvdp/bench/sequence.h"

#include <cstdio>

#include "gvdp/base/error.h"
#include "gvdp/sched/memory_estimate.h"
#include "gvdp/sched/mesh_scene.h"

namespace gvdp::detail {

void validate(const SequenceOptions& o) {
  if (o.mesh.empty())
    findScene(o.scene);
  else
    validateLattice(o.lattice);
  validate(static_cast<const RendererOptions&>(o));
  GVDP_INPUT_CHECK(o.frames >= 1 && o.frames <= 1000000, "bad --frames ", o.frames,
                   " (expected 1..1000000)");
  GVDP_INPUT_CHECK(o.again >= 0 && o.again <= 1000, "bad repeat count ", o.again,
                   " (expected 0..1000)");
  const double LIMIT = 1e8;  // int32 brick coordinates at level 0 hold about 2.7e8 units
  GVDP_INPUT_CHECK(
      std::abs(o.origin.x) < LIMIT && std::abs(o.origin.y) < LIMIT && std::abs(o.origin.z) < LIMIT,
      "bad --origin ", o.origin.x, ",", o.origin.y, ",", o.origin.z,
      " (each coordinate within 1e8)");
}

namespace {

std::string gigabytes(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GB", static_cast<double>(bytes) / 1e9);
  return text;
}

// "scheduler sp at 160x100 with a pool of 32768 bricks", or "<what> (scheduler sp at 160x100)".
std::string describe(const SequenceOptions& o, const std::string& what) {
  std::string d = "scheduler " + std::string(schedulerName(o.scheduler.kind)) + " at " +
                  std::to_string(o.width) + "x" + std::to_string(o.height);
  if (!what.empty()) return what + " (" + d + ")";
  if (o.scheduler.kind == SchedulerKind::Direct) return d;
  return d + " with a pool of " + std::to_string(poolBricksOf(o.scheduler)) + " bricks";
}

}  // namespace

void checkResources(const SequenceOptions& o, const std::string& what) {
  requireBackend(o.scheduler.backend);
  std::optional<uint64_t> have = backendMemoryBytes(o.scheduler.backend);
  if (!have) return;  // nothing to compare with: the allocations will tell
  // The structures follow the largest tile's rays; the image is the whole frame's.
  FrameSetup frame = frameOf(o, 0);
  PixelTile largest{0, 0, 0, 0};
  for (const PixelTile& t : initialTiles(frame.width, frame.height, o.tiles))
    if (t.pixels() > largest.pixels()) largest = t;
  uint64_t need = memoryTotal(memoryEstimate(
      o.scheduler, tileOf(frame, largest.x, largest.y, largest.width, largest.height)));
  if (largest.pixels() != frame.pixelCount())
    need += static_cast<uint64_t>(frame.pixelCount()) * sizeof(uint32_t);
  bool cuda = o.scheduler.backend == Backend::Cuda;
  GVDP_INPUT_CHECK(need <= *have, describe(o, what), " needs ", gigabytes(need), " on the ",
                   backendName(o.scheduler.backend), " backend, which has ", gigabytes(*have),
                   cuda ? " of device memory free" : " of memory available");
}

std::string worldName(const SequenceOptions& o) {
  if (o.mesh.empty()) return o.scene;
  size_t slash = o.mesh.find_last_of('/');
  return "mesh:" + o.mesh.substr(slash == std::string::npos ? 0 : slash + 1);
}

std::unique_ptr<Renderer> makeSequenceRenderer(const SequenceOptions& o) {
  if (o.mesh.empty()) return makeRenderer(o.scene, o);
  return std::make_unique<Renderer>(
      o, MeshScene::load(o.mesh, o.lattice, o.scheduler.backend)->kernels());
}

CameraPose poseOf(const SequenceOptions& o, int frame) {
  bool mesh = !o.mesh.empty();
  CameraPose start = mesh ? meshStart(o.lattice) : findScene(o.scene).start;
  start.position = start.position + o.origin;
  return cameraAt(o.movement, start, mesh ? MESH_SPEED : findScene(o.scene).speed, frame);
}

FrameSetup frameOf(const SequenceOptions& o, int frame) {
  float voxelSize0 = o.mesh.empty() ? findScene(o.scene).world.voxelSize0() : MESH_VOXEL_SIZE0;
  return frameOf(o, voxelSize0, poseOf(o, frame), frame);
}

MemoryReport renderSequence(const SequenceOptions& o,
                            const std::function<void(const Image&, const FrameStats&)>& onFrame,
                            const TileProgress& onTile) {
  validate(o);
  checkResources(o);
  std::unique_ptr<Renderer> renderer = makeSequenceRenderer(o);
  renderer->onTile(onTile);
  Image image;
  for (int f = 0; f < o.frames + o.again; ++f) {
    FrameStats stats = renderer->render(poseOf(o, f < o.frames ? f : o.frames - 1), image);
    onFrame(image, stats);
  }
  return renderer->memory();
}

}  // namespace gvdp::detail
