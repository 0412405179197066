// Statistics of a run's frame times, as the paper reports them (4.2): average FPS, 1% low FPS
// (the mean of the slowest 1% of frames, at least one frame), median and 99th percentile.
#pragma once

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "gvdp/sched/scheduler.h"

namespace gvdp::detail {

struct FrameTimeStats {
  double avgFps = 0, low1Fps = 0, medianMs = 0, p99Ms = 0;
};

inline FrameTimeStats frameTimeStats(std::vector<double> ms) {
  FrameTimeStats s;
  if (ms.empty()) return s;
  std::sort(ms.begin(), ms.end());
  size_t n = ms.size();
  double total = std::accumulate(ms.begin(), ms.end(), 0.0);
  s.avgFps = 1000.0 * static_cast<double>(n) / total;
  size_t slow = std::max<size_t>(1, n / 100);
  s.low1Fps = 1000.0 * static_cast<double>(slow) / std::accumulate(ms.end() - slow, ms.end(), 0.0);
  s.medianMs = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
  // Nearest-rank percentile.
  s.p99Ms = ms[std::min(n - 1, static_cast<size_t>(std::ceil(0.99 * static_cast<double>(n))) - 1)];
  return s;
}

// A run's slowest frame (its 1% low with fewer than 100 frames) and what it asked for: its
// position among the frames, its bricks (produced and EMPTY) over the run's mean, and its time
// over the time the run's other frames predict for its bricks (overPredicted: a least-squares
// line of ms against bricks through the other frames, its slope at least 0; 0 with fewer than 3
// frames). A slowest frame of several times the mean bricks is a spike of the camera's path (a
// sphere left, a corridor opening): exact frames produce all of them in that frame, whatever the
// scheduler. overPredicted near 1 says the frame is as slow as its work, whatever its bricks; well
// over 1, slower than its bricks explain: a latency (a chain of productions, a stall).
struct SlowestFrame {
  size_t index = 0;
  double bricksOverMean = 0;
  double overPredicted = 0;
};

inline SlowestFrame slowestFrame(const std::vector<double>& ms,
                                 const std::vector<uint64_t>& bricks) {
  SlowestFrame s;
  if (ms.empty() || bricks.size() != ms.size()) return s;
  s.index = static_cast<size_t>(std::max_element(ms.begin(), ms.end()) - ms.begin());
  double mean = static_cast<double>(std::accumulate(bricks.begin(), bricks.end(), uint64_t{0})) /
                static_cast<double>(bricks.size());
  s.bricksOverMean = mean > 0 ? static_cast<double>(bricks[s.index]) / mean : 0.0;
  if (ms.size() < 3) return s;
  double n = static_cast<double>(ms.size() - 1), mx = 0, my = 0;
  for (size_t i = 0; i < ms.size(); ++i)
    if (i != s.index) {
      mx += static_cast<double>(bricks[i]) / n;
      my += ms[i] / n;
    }
  double sxx = 0, sxy = 0;
  for (size_t i = 0; i < ms.size(); ++i)
    if (i != s.index) {
      double dx = static_cast<double>(bricks[i]) - mx;
      sxx += dx * dx;
      sxy += dx * (ms[i] - my);
    }
  double slope = sxx > 0 ? std::max(sxy / sxx, 0.0) : 0.0;
  double predicted = my + slope * (static_cast<double>(bricks[s.index]) - mx);
  s.overPredicted = predicted > 0 ? ms[s.index] / predicted : 0.0;
  return s;
}

// A budgeted run (--budget-ms): frames whose time was within the budget, and the share of all
// their pixels that showed a coarser level for a brick that was not ready.
struct BudgetStats {
  size_t framesWithin = 0;
  double coarserShare = 0;
};

inline BudgetStats budgetStats(const std::vector<FrameStats>& frames, double budgetMs,
                               int64_t pixels) {
  BudgetStats b;
  uint64_t coarser = 0;
  for (const FrameStats& f : frames) {
    b.framesWithin += f.ms <= budgetMs ? 1u : 0u;
    coarser += f.cache.coarser;
  }
  if (!frames.empty())
    b.coarserShare = static_cast<double>(coarser) /
                     (static_cast<double>(pixels) * static_cast<double>(frames.size()));
  return b;
}

}  // namespace gvdp::detail
