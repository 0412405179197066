#include "gvdp/serve/params.h"

#include <charconv>
#include <cmath>

#include "gvdp/base/error.h"
#include "gvdp/world/registry.h"

namespace gvdp::detail {

std::string printable(std::string_view text) {
  std::string s;
  for (char c : text.substr(0, 40)) s += (c >= 32 && c < 127) ? c : '?';
  return text.size() > 40 ? s + "..." : s;
}

int64_t parseIntParam(std::string_view name, std::string_view text, int64_t lo, int64_t hi) {
  int64_t v = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  GVDP_INPUT_CHECK(
      !text.empty() && ec == std::errc() && end == text.data() + text.size() && v >= lo && v <= hi,
      "bad ", name, " '", printable(text), "' (expected an integer ", lo, "..", hi, ")");
  return v;
}

double parseNumberParam(std::string_view name, std::string_view text, double lo, double hi) {
  double v = 0.0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  GVDP_INPUT_CHECK(!text.empty() && ec == std::errc() && end == text.data() + text.size() &&
                       std::isfinite(v) && v >= lo && v <= hi,
                   "bad ", name, " '", printable(text), "' (expected a number ", lo, "..", hi, ")");
  return v;
}

Vec3f parseVec3Param(std::string_view name, std::string_view text, float lo, float hi) {
  float v[3];
  std::string_view rest = text;
  for (int i = 0; i < 3; ++i) {
    size_t comma = i < 2 ? rest.find(',') : rest.size();
    GVDP_INPUT_CHECK(comma != std::string_view::npos, "bad ", name, " '", printable(text),
                     "' (expected x,y,z)");
    v[i] = static_cast<float>(parseNumberParam(name, rest.substr(0, comma), lo, hi));
    rest = i < 2 ? rest.substr(comma + 1) : std::string_view{};
  }
  return {v[0], v[1], v[2]};
}

std::string parseClientId(std::string_view text) {
  bool ok = !text.empty() && text.size() <= 32;
  for (char c : text)
    ok = ok && ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                c == '-' || c == '_');
  GVDP_INPUT_CHECK(ok, "bad client '", printable(text), "' (expected 1..32 of a-z A-Z 0-9 - _)");
  return std::string(text);
}

ViewSettings parseViewSettings(const ViewSettings& current, Backend backend, const ViewParams& p) {
  const auto& [scene, scheduler, width, height, budget, path] = p;
  ViewSettings s = current;
  if (scene) s.scene = std::string(findScene(*scene).name);
  if (scheduler) {
    s.scheduler = parseScheduler(*scheduler);
    GVDP_INPUT_CHECK(s.scheduler != SchedulerKind::Direct,
                     "bad scheduler 'direct' (the viewer "
                     "shows a cached scheduler: sp, dp, pt or graph)");
    GVDP_INPUT_CHECK(s.scheduler != SchedulerKind::Graph || backend == Backend::Cuda,
                     "bad scheduler 'graph' (it runs on the cuda backend only)");
  }
  if (width)
    s.width = static_cast<int>(parseIntParam("width", *width, MIN_VIEW_SIZE, MAX_VIEW_WIDTH));
  if (height)
    s.height = static_cast<int>(parseIntParam("height", *height, MIN_VIEW_SIZE, MAX_VIEW_HEIGHT));
  if (budget)
    s.budgetMs =
        *budget == "off" ? NO_BUDGET : parseNumberParam("budget", *budget, 0.0, MAX_VIEW_BUDGET_MS);
  if (path) s.path = *path == "free" ? std::nullopt : std::optional(parseMovement(*path));
  return s;
}

std::string pathName(const std::optional<Movement>& path) {
  return path ? std::string(movementName(*path)) : "free";
}

}  // namespace gvdp::detail
