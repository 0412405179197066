#include "gvdp/io/ray_cost_map.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "gvdp/io/draw.h"
#include "gvdp/io/png.h"

namespace gvdp::detail {
namespace {

CostQuantiles quantilesOf(const std::vector<uint32_t>& v, int width) {
  CostQuantiles q;
  double sum = 0.0;
  for (size_t p = 0; p < v.size(); ++p) {
    sum += v[p];
    if (v[p] > q.max) {
      q.max = v[p];
      q.maxX = static_cast<int>(p % static_cast<size_t>(width));
      q.maxY = static_cast<int>(p / static_cast<size_t>(width));
    }
  }
  q.mean = sum / static_cast<double>(v.size());
  std::vector<uint32_t> sorted = v;
  std::sort(sorted.begin(), sorted.end());
  // Nearest rank: the smallest value with at least a share f of the values at most it.
  auto rank = [&](double f) {
    size_t k = static_cast<size_t>(std::ceil(f * static_cast<double>(sorted.size())));
    return sorted[std::min(sorted.size(), std::max<size_t>(k, 1)) - 1];
  };
  q.p50 = rank(0.5);
  q.p99 = rank(0.99);
  q.p999 = rank(0.999);
  return q;
}

// A perceptual ramp (close to matplotlib's inferno), t in [0, 1].
uint32_t heat(double t) {
  static const int STOPS[][3] = {
      {0, 0, 4}, {87, 16, 110}, {188, 55, 84}, {249, 142, 9}, {252, 255, 164}};
  constexpr int LAST = 4;
  t = std::clamp(t, 0.0, 1.0) * LAST;
  int i = std::min(static_cast<int>(t), LAST - 1);
  double f = t - i;
  auto mix = [&](int c) {
    return static_cast<int>(std::lround(STOPS[i][c] + f * (STOPS[i + 1][c] - STOPS[i][c])));
  };
  return rgb(mix(0), mix(1), mix(2));
}

// Where a value lies on a log scale from 0 to `max`.
double logScale(uint32_t v, uint32_t max) {
  return max == 0 ? 0.0 : std::log1p(static_cast<double>(v)) / std::log1p(static_cast<double>(max));
}

constexpr int MARGIN = 8, MIN_PANEL = 240;  // a panel wide enough for its labels at scale 1
const uint32_t BACKGROUND = rgb(255, 255, 255), INK = rgb(20, 20, 20);

// The picture's layout: its text scaled with the panels (one scale step per 400 pixels).
struct Layout {
  int scale, title, label, bar, legend;
  explicit Layout(int width)
      : scale(std::max(1, width / 400)),
        title(20 * scale),
        label(24 * scale),
        bar(10 * scale),
        legend(bar + 16 * scale) {}
};

void drawPanel(Image& im, const Layout& l, int x0, const RayCosts& c,
               const std::vector<uint32_t>& v, const CostQuantiles& q, const std::string& what) {
  char label[160];
  std::snprintf(label, sizeof label, "mean %.3g, p99 %u, max %u at (%d, %d)", q.mean, q.p99, q.max,
                q.maxX, q.maxY);
  drawText(im, x0, l.title, what + " per ray", INK, l.scale);
  drawText(im, x0, l.title + l.label / 2 + 4, label, INK, l.scale);
  const int y0 = l.title + l.label;
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x)
      im.pixels[static_cast<size_t>(y0 + y) * im.width + x0 + x] =
          heat(logScale(v[static_cast<size_t>(y) * c.width + x], q.max));
  const int yb = y0 + c.height + 4;
  for (int x = 0; x < c.width; ++x)
    fillRect(im, x0 + x, yb, x0 + x + 1, yb + l.bar,
             heat(static_cast<double>(x) / std::max(1, c.width - 1)));
  drawText(im, x0, yb + l.bar + 3, "0", INK, l.scale);
  std::string top = std::to_string(q.max) + " (log scale)";
  drawText(im, x0 + c.width - 6 * l.scale * static_cast<int>(top.size()), yb + l.bar + 3, top, INK,
           l.scale);
}

}  // namespace

RayCostSummary summarizeRayCosts(const RayCosts& c) {
  return {quantilesOf(c.lookups, c.width), quantilesOf(c.samples, c.width),
          quantilesOf(c.stops, c.width)};
}

std::string rayCostLine(const RayCostSummary& s) {
  char line[240];
  std::snprintf(line, sizeof line,
                "lookups per ray %.1f (p99 %u, max %u at %d,%d)  samples %.1f (p99 %u, max %u)  "
                "stops %.2f (p99 %u, max %u at %d,%d)",
                s.lookups.mean, s.lookups.p99, s.lookups.max, s.lookups.maxX, s.lookups.maxY,
                s.samples.mean, s.samples.p99, s.samples.max, s.stops.mean, s.stops.p99,
                s.stops.max, s.stops.maxX, s.stops.maxY);
  return line;
}

Image rayCostImage(const RayCosts& c, const RayCostSummary& s, const std::string& title) {
  const int panel = std::max(c.width, MIN_PANEL);
  const Layout l(c.width);
  Image im(3 * panel + 4 * MARGIN, l.title + l.label + c.height + 4 + l.legend);
  std::fill(im.pixels.begin(), im.pixels.end(), BACKGROUND);
  drawText(im, MARGIN, 5, title, INK, l.scale);
  drawPanel(im, l, MARGIN, c, c.lookups, s.lookups, "brick lookups");
  drawPanel(im, l, 2 * MARGIN + panel, c, c.samples, s.samples, "samples");
  drawPanel(im, l, 3 * MARGIN + 2 * panel, c, c.stops, s.stops, "stops (productions waited on)");
  return im;
}

RayCostSummary writeRayCostMap(const RayCosts& c, const std::string& title,
                               const std::string& path) {
  RayCostSummary s = summarizeRayCosts(c);
  writePng(rayCostImage(c, s, title), path);
  return s;
}

}  // namespace gvdp::detail
