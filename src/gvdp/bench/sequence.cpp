#include "gvdp/bench/sequence.h"

#include <cstdio>

#include "gvdp/base/error.h"
#include "gvdp/sched/graph/graph.h"
#include "gvdp/sched/memory_estimate.h"

namespace gvdp {

void validate(const SequenceOptions& o) {
  findScene(o.scene);
  GVDP_INPUT_CHECK(o.width >= 8 && o.width <= 16384, "bad --width ", o.width,
                   " (expected 8..16384)");
  GVDP_INPUT_CHECK(o.height >= 8 && o.height <= 16384, "bad --height ", o.height,
                   " (expected 8..16384)");
  GVDP_INPUT_CHECK(static_cast<int64_t>(o.width) * o.height <= 64ll << 20, "bad size ", o.width,
                   "x", o.height, " (at most 64 Mpixels)");
  GVDP_INPUT_CHECK(o.frames >= 1 && o.frames <= 1000000, "bad --frames ", o.frames,
                   " (expected 1..1000000)");
  GVDP_INPUT_CHECK(o.levels >= 1 && o.levels <= MAX_LEVELS, "bad --levels ", o.levels,
                   " (expected 1..", MAX_LEVELS, ")");
  GVDP_INPUT_CHECK(o.fovDegrees >= 1.0f && o.fovDegrees <= 150.0f, "bad --fov ", o.fovDegrees,
                   " (expected 1..150 degrees)");
  const double LIMIT = 1e8;  // int32 brick coordinates at level 0 hold about 2.7e8 units
  GVDP_INPUT_CHECK(
      std::abs(o.origin.x) < LIMIT && std::abs(o.origin.y) < LIMIT && std::abs(o.origin.z) < LIMIT,
      "bad --origin ", o.origin.x, ",", o.origin.y, ",", o.origin.z,
      " (each coordinate within 1e8)");
  if (o.scheduler.kind == SchedulerKind::Graph) graphDriverFromEnvironment();
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
  uint64_t need = memoryTotal(memoryEstimate(o.scheduler, frameOf(o, 0)));
  bool cuda = o.scheduler.backend == Backend::Cuda;
  GVDP_INPUT_CHECK(need <= *have, describe(o, what), " needs ", gigabytes(need), " on the ",
                   backendName(o.scheduler.backend), " backend, which has ", gigabytes(*have),
                   cuda ? " of device memory free" : " of memory available");
}

FrameSetup frameOf(const SequenceOptions& o, int frame) {
  const SceneInfo& scene = findScene(o.scene);
  CameraPose start = scene.start;
  start.position = start.position + o.origin;
  CameraPose pose = cameraAt(o.movement, start, scene.speed, frame);
  return makeFrame(pose, scene.params, o.width, o.height, o.levels, frame, o.fovDegrees);
}

MemoryReport renderSequence(const SequenceOptions& o,
                            const std::function<void(const Image&, const FrameStats&)>& onFrame) {
  validate(o);
  checkResources(o);
  std::unique_ptr<Scheduler> scheduler = makeScheduler(o.scheduler);
  Image image;
  for (int f = 0; f < o.frames; ++f) {
    FrameStats stats = scheduler->render(frameOf(o, f), image);
    onFrame(image, stats);
  }
  return scheduler->memory();
}

}  // namespace gvdp
