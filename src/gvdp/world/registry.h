// The built-in scenes by name: parameters, a one-line description, a start camera with both
// matter and empty space in view, and the walking speed of the camera paths.
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "gvdp/base/camera.h"
#include "gvdp/world/scene.h"

namespace gvdp::detail {

struct SceneInfo {
  std::string_view name;
  std::string_view description;
  BuiltinScene world;
  CameraPose start;
  float speed;  // world units per frame along the camera paths
};

std::span<const SceneInfo> allScenes();
// Throws InputError naming the value and the valid names.
const SceneInfo& findScene(std::string_view name);
std::string sceneNames();  // "perlin, fbm, ..."

}  // namespace gvdp::detail
