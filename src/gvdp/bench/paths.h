// The five camera movements of the paper's benchmark (4.1), deterministic in the frame index:
// walkthrough (forward with gentle turns and bobbing), forward, backward, sideways, spinning;
// and orbit, for finite objects (meshes): around the vertical axis through the world's origin,
// looking at it, at the start's height and distance.
#pragma once

#include <string>
#include <string_view>

#include "gvdp/base/camera.h"

namespace gvdp::detail {

enum class Movement { Walkthrough, Forward, Backward, Sideways, Spinning, Orbit };
constexpr int MOVEMENT_COUNT = 6;

std::string_view movementName(Movement m);
Movement parseMovement(std::string_view name);  // throws InputError
std::string movementNames();

// Pose at `frame` for a path starting at `start`, moving `speed` world units per frame.
CameraPose cameraAt(Movement m, const CameraPose& start, float speed, int frame);

}  // namespace gvdp::detail
