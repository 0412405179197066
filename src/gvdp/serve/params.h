// Request parameters of `gvdp serve`, parsed and bounded: every value a client sends is checked
// here, and a bad one throws InputError naming it (the server answers 400 with that line).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "gvdp/base/vecmath.h"
#include "gvdp/bench/paths.h"
#include "gvdp/renderer.h"

namespace gvdp::detail {

// What the page chooses: the world, the scheduler, the image size, the frame-time budget and
// the camera: flown by the driver (no path) or following one of the benchmark's camera paths
// (one path frame per rendered frame) until the driver moves it.
struct ViewSettings {
  std::string scene = "perlin";
  SchedulerKind scheduler = SchedulerKind::Pt;
  int width = 0, height = 0;
  double budgetMs = NO_BUDGET;
  std::optional<Movement> path;
};
// "free" or the path's name.
std::string pathName(const std::optional<Movement>& path);

// A live view's bounds: an image of at most 3840x2160 (4K), a budget of at most 1000 ms.
constexpr int MAX_VIEW_WIDTH = 3840, MAX_VIEW_HEIGHT = 2160, MIN_VIEW_SIZE = 16;
constexpr double MAX_VIEW_BUDGET_MS = 1000.0;

// Text from a client as it may be echoed in a message: at most 40 printable characters.
std::string printable(std::string_view text);
// The whole string as one number within [lo, hi].
int64_t parseIntParam(std::string_view name, std::string_view text, int64_t lo, int64_t hi);
double parseNumberParam(std::string_view name, std::string_view text, double lo, double hi);
// "x,y,z", each within [lo, hi].
Vec3f parseVec3Param(std::string_view name, std::string_view text, float lo, float hi);
// A client's id: 1..32 letters, digits, '-' or '_'.
std::string parseClientId(std::string_view text);

// A view's parameters as a request gives them (absent: nullopt): scene, scheduler (not direct:
// the viewer shows a cached renderer; graph needs the cuda backend), width, height, budget
// ("off" or milliseconds), path ("free" or a movement).
struct ViewParams {
  std::optional<std::string> scene, scheduler, width, height, budget, path;
};
// `current` with the parameters given replaced.
ViewSettings parseViewSettings(const ViewSettings& current, Backend backend, const ViewParams& p);

}  // namespace gvdp::detail
