#include "gvdp/io/timeline_export.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "gvdp/io/draw.h"

namespace gvdp::detail {
namespace {

struct Interval {
  uint64_t a, b;
};

// Total length of the union of intervals.
uint64_t unionLength(std::vector<Interval> v) {
  std::sort(v.begin(), v.end(), [](const Interval& x, const Interval& y) { return x.a < y.a; });
  uint64_t total = 0, a = 0, b = 0;
  bool open = false;
  for (const Interval& i : v) {
    if (open && i.a <= b) {
      b = std::max(b, i.b);
      continue;
    }
    if (open) total += b - a;
    a = i.a;
    b = i.b;
    open = true;
  }
  return open ? total + (b - a) : total;
}

uint64_t frameStart(const std::vector<TimelineRecord>& r) {
  uint64_t s = ~0ull;
  for (const TimelineRecord& x : r) s = std::min(s, x.start);
  return r.empty() ? 0 : s;
}
uint64_t frameEnd(const std::vector<TimelineRecord>& r) {
  uint64_t e = 0;
  for (const TimelineRecord& x : r) e = std::max(e, x.end);
  return e;
}

const uint32_t KIND_COLOUR[TASK_KIND_COUNT] = {rgb(220, 40, 40),  rgb(50, 90, 230),
                                               rgb(60, 190, 80),  rgb(230, 200, 40),
                                               rgb(240, 140, 30), rgb(40, 190, 200)};
const uint32_t BOTH_COLOUR = rgb(170, 60, 200);  // render and production on one SM
const uint32_t IDLE_COLOUR = rgb(0, 0, 0);
const uint32_t BACKGROUND = rgb(255, 255, 255);
const uint32_t INK = rgb(20, 20, 20);

}  // namespace

TimelineStats timelineStats(const std::vector<TimelineRecord>& records, int lanes) {
  TimelineStats s;
  s.lanes = lanes;
  s.records = records.size();
  if (records.empty() || lanes <= 0) return s;
  uint64_t t0 = frameStart(records), t1 = frameEnd(records);
  double span = static_cast<double>(t1 - t0);
  s.spanMs = span * 1e-6;
  std::vector<std::vector<Interval>> all(lanes),
      byKind(static_cast<size_t>(lanes) * TASK_KIND_COUNT);
  for (const TimelineRecord& r : records) {
    int lane = std::min<int>(r.smStart, lanes - 1);
    all[lane].push_back({r.start, r.end});
    byKind[static_cast<size_t>(lane) * TASK_KIND_COUNT + static_cast<int>(r.kind)].push_back(
        {r.start, r.end});
  }
  double busy = 0;
  for (int l = 0; l < lanes; ++l) {
    busy += static_cast<double>(unionLength(all[l]));
    for (int k = 0; k < TASK_KIND_COUNT; ++k)
      s.busyFraction[k] +=
          static_cast<double>(unionLength(byKind[static_cast<size_t>(l) * TASK_KIND_COUNT + k]));
  }
  for (double& f : s.busyFraction) f /= span * lanes;
  s.idleFraction = span > 0 ? 1.0 - busy / (span * lanes) : 0.0;
  // Tail: from the scheduling work (render, production, sweep; not the final resolve nor the
  // cache upkeep, which run full-width by construction, nor the prefetch, which fills idle
  // lanes), the time at its end during which fewer than half the lanes are busy.
  std::vector<std::vector<Interval>> work(lanes);
  uint64_t workEnd = t0;
  for (const TimelineRecord& r : records) {
    if (r.kind == TaskKind::Resolve || r.kind == TaskKind::Cache || r.kind == TaskKind::Prefetch)
      continue;
    work[std::min<int>(r.smStart, lanes - 1)].push_back({r.start, r.end});
    workEnd = std::max(workEnd, r.end);
  }
  std::vector<std::pair<uint64_t, int>> events;
  for (int l = 0; l < lanes; ++l) {
    std::vector<Interval> v = work[l];
    std::sort(v.begin(), v.end(), [](const Interval& x, const Interval& y) { return x.a < y.a; });
    uint64_t a = 0, b = 0;
    bool open = false;
    for (const Interval& i : v) {
      if (open && i.a <= b) {
        b = std::max(b, i.b);
        continue;
      }
      if (open) events.push_back({a, +1}), events.push_back({b, -1});
      a = i.a, b = i.b, open = true;
    }
    if (open) events.push_back({a, +1}), events.push_back({b, -1});
  }
  std::sort(events.begin(), events.end());
  int active = 0;
  uint64_t lastHalfBusy = t0;
  for (const auto& [t, d] : events) {
    if (active * 2 >= lanes) lastHalfBusy = t;  // busy enough up to this event
    active += d;
  }
  s.tailMs = static_cast<double>(workEnd - lastHalfBusy) * 1e-6;
  return s;
}

std::string timelineSummary(const TimelineStats& s) {
  char line[512];
  std::snprintf(
      line, sizeof line,
      "timeline: %.3f ms over %d lanes, %zu records; busy render %.1f%% production "
      "%.1f%% resolve %.1f%% cache %.1f%% sweep %.1f%% prefetch %.1f%%; idle %.1f%%; tail "
      "%.3f ms",
      s.spanMs, s.lanes, s.records, 100 * s.busyFraction[0], 100 * s.busyFraction[1],
      100 * s.busyFraction[2], 100 * s.busyFraction[3], 100 * s.busyFraction[4],
      100 * s.busyFraction[5], 100 * s.idleFraction, s.tailMs);
  return line;
}

Image timelineImage(const std::vector<TimelineRecord>& records, int lanes,
                    const std::string& title) {
  const int LEFT = 70, TOP = 46, PLOT_H = 900;
  int cell = std::max(2, 1200 / std::max(lanes, 1));
  Image im(LEFT + lanes * cell + 20, TOP + PLOT_H + 30);
  std::fill(im.pixels.begin(), im.pixels.end(), BACKGROUND);
  uint64_t t0 = frameStart(records), t1 = std::max(frameEnd(records), t0 + 1);
  double nsPerRow = static_cast<double>(t1 - t0) / PLOT_H;
  // Per lane and row: which kinds ran during that row's time.
  std::vector<uint8_t> mask(static_cast<size_t>(lanes) * PLOT_H, 0);
  for (const TimelineRecord& r : records) {
    int lane = std::min<int>(r.smStart, lanes - 1);
    int a = static_cast<int>(static_cast<double>(r.start - t0) / nsPerRow);
    int b = static_cast<int>(static_cast<double>(r.end - t0) / nsPerRow);
    for (int row = std::max(a, 0); row <= std::min(b, PLOT_H - 1); ++row)
      mask[static_cast<size_t>(lane) * PLOT_H + row] |=
          static_cast<uint8_t>(1u << static_cast<int>(r.kind));
  }
  for (int lane = 0; lane < lanes; ++lane)
    for (int row = 0; row < PLOT_H; ++row) {
      uint8_t m = mask[static_cast<size_t>(lane) * PLOT_H + row];
      uint32_t c = IDLE_COLOUR;
      if ((m & 3u) == 3u) {
        c = BOTH_COLOUR;
      } else {
        for (int k = 0; k < TASK_KIND_COUNT; ++k)
          if (m & (1u << k)) {
            c = KIND_COLOUR[k];
            break;
          }
      }
      fillRect(im, LEFT + lane * cell, TOP + row, LEFT + (lane + 1) * cell, TOP + row + 1, c);
    }
  // Title, legend, time scale.
  drawText(im, LEFT, 6, title, INK);
  int x = LEFT;
  for (int k = 0; k < TASK_KIND_COUNT; ++k) {
    fillRect(im, x, 24, x + 10, 34, KIND_COLOUR[k]);
    drawText(im, x + 14, 25, taskKindName(static_cast<TaskKind>(k)), INK);
    x += 110;
  }
  fillRect(im, x, 24, x + 10, 34, BOTH_COLOUR);
  drawText(im, x + 14, 25, "render+production", INK);
  x += 150;
  fillRect(im, x, 24, x + 10, 34, IDLE_COLOUR);
  drawText(im, x + 14, 25, "idle", INK);
  double spanMs = static_cast<double>(t1 - t0) * 1e-6;
  for (int i = 0; i <= 10; ++i) {
    int y = TOP + i * (PLOT_H - 1) / 10;
    fillRect(im, LEFT - 6, y, LEFT, y + 1, INK);
    char label[32];
    std::snprintf(label, sizeof label, "%.2f ms", spanMs * i / 10.0);
    drawText(im, 4, y - 3, label, INK);
  }
  char axis[64];
  std::snprintf(axis, sizeof axis, "%d lanes (SMs or worker threads), time from the top", lanes);
  drawText(im, LEFT, TOP + PLOT_H + 10, axis, INK);
  return im;
}

std::string chromeTraceJson(const std::vector<TimelineRecord>& records, int lanes) {
  nlohmann::json events = nlohmann::json::array();
  uint64_t t0 = frameStart(records);
  for (int l = 0; l < lanes; ++l)
    events.push_back({{"name", "thread_name"},
                      {"ph", "M"},
                      {"pid", 0},
                      {"tid", l},
                      {"args", {{"name", "SM " + std::to_string(l)}}}});
  for (const TimelineRecord& r : records)
    events.push_back({{"name", taskKindName(r.kind)},
                      {"cat", taskKindName(r.kind)},
                      {"ph", "X"},
                      {"pid", 0},
                      {"tid", r.smStart},
                      {"ts", static_cast<double>(r.start - t0) * 1e-3},
                      {"dur", static_cast<double>(r.end - r.start) * 1e-3}});
  return nlohmann::json{{"traceEvents", events}, {"displayTimeUnit", "ms"}}.dump();
}

}  // namespace gvdp::detail
