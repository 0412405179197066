// A frame sequence: a built-in scene or a mesh, a camera movement and a renderer's options,
// rendered frame by frame through the public Renderer (include/gvdp/renderer.h). The `render`
// command, the tests and the benchmark all go through here.
#pragma once

#include <functional>
#include <string>

#include "gvdp/bench/paths.h"
#include "gvdp/renderer.h"
#include "gvdp/world/registry.h"

namespace gvdp::detail {

// A renderer's options (scheduler, size, levels, field of view) and the sequence's own.
struct SequenceOptions : RendererOptions {
  std::string scene = "perlin";
  std::string mesh;   // a mesh file (OFF, PLY, OBJ): the world instead of `scene`
  float lattice = 0;  // the mesh's copies in x and z this far apart (0: one model)
  Movement movement = Movement::Walkthrough;
  int frames = 8;
  int again = 0;          // the last pose rendered this many times more (from the cache it filled)
  Vec3d origin{0, 0, 0};  // added to the scene's start position
};

// Throws InputError naming the first bad value.
void validate(const SequenceOptions& options);

// After validate(): throws InputError when the backend is unavailable or when the structures of
// the sequence (memory_estimate.h) do not fit in what the backend can hold now. `what` names the
// configuration in the message, e.g. "--pool-mb 190000" (default: scheduler, size and pool).
void checkResources(const SequenceOptions& options, const std::string& what = "");

// The world's name: the scene's, or "mesh:" and the mesh file's name.
std::string worldName(const SequenceOptions& options);
// A renderer of the sequence's world (a mesh: read, placed and its kd-tree built here).
std::unique_ptr<Renderer> makeSequenceRenderer(const SequenceOptions& options);

CameraPose poseOf(const SequenceOptions& options, int frame);
// The frame a renderer makes of poseOf(options, frame) as its frame number `frame`.
FrameSetup frameOf(const SequenceOptions& options, int frame);

// Renders every frame in order (after validate() and checkResources()); onFrame sees each image
// and its stats, `onTile` each tile of a tiled frame. Returns the memory the scheduler held.
MemoryReport renderSequence(const SequenceOptions& options,
                            const std::function<void(const Image&, const FrameStats&)>& onFrame,
                            const TileProgress& onTile = {});

}  // namespace gvdp::detail
