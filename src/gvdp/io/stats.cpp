#include "gvdp/io/stats.h"

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "gvdp/base/error.h"
#include "gvdp/base/gpu.h"

namespace gvdp::detail {

namespace {
nlohmann::json quantilesJson(const CostQuantiles& q) {
  return {{"mean", q.mean}, {"p50", q.p50}, {"p99", q.p99},
          {"p999", q.p999}, {"max", q.max}, {"max_pixel", {q.maxX, q.maxY}}};
}
}  // namespace

std::string statsJson(const SequenceOptions& o, const std::vector<FrameStats>& frames,
                      const MemoryReport& memory, const std::vector<RayCostSummary>& costs) {
  GVDP_CHECK(costs.empty() || costs.size() == frames.size(), "stats.json: ", costs.size(),
             " ray-cost summaries for ", frames.size(), " frames");
  nlohmann::json j;
  j["scene"] = worldName(o);
  if (!o.mesh.empty()) {
    j["mesh"] = o.mesh;
    j["lattice"] = o.lattice;
  }
  j["movement"] = movementName(o.movement);
  j["backend"] = backendName(o.scheduler.backend);
  j["scheduler"] = schedulerName(o.scheduler.kind);
  j["width"] = o.width;
  j["height"] = o.height;
  j["levels"] = o.levels;
  j["lod_width"] = o.lodWidth ? o.lodWidth : std::min(o.width, MAX_LOD_WIDTH);
  SchedulerOptions used = resolvedOptions(o.scheduler);  // 0: the scheduler has none
  if (used.poolBricks) j["pool_bricks"] = used.poolBricks;
  if (used.pendingLaunches) j["pending_launches"] = used.pendingLaunches;
  if (used.kind == SchedulerKind::Pt) j["lookahead"] = used.lookahead;
  if (used.kind == SchedulerKind::Pt) j["tail_lookahead"] = ptTailLookahead(used);
  if (used.kind == SchedulerKind::Pt) j["prefetch"] = used.prefetch;
  if (used.kind == SchedulerKind::Pt) j["far_prefetch"] = used.farPrefetch;
  if (used.budgetMs >= 0.0) j["budget_ms"] = used.budgetMs;
  j["tiles"] = o.tiles.mode == TileOptions::Mode::Auto  ? "auto"
               : o.tiles.mode == TileOptions::Mode::Off ? "off"
                                                        : std::to_string(o.tiles.grid);
  j["tile_plan"] = o.tiles.plan;
  if (o.scheduler.backend == Backend::Cuda) j["device"] = cudaDeviceSummary();
  nlohmann::json mem = nlohmann::json::object();
  for (const MemoryItem& m : memory) mem[m.name] = m.bytes;
  j["memory"] = mem;
  nlohmann::json list = nlohmann::json::array();
  for (const FrameStats& f : frames)
    list.push_back({{"index", f.index},
                    {"ms", f.ms},
                    {"passes", f.passes},
                    {"bricks_requested", f.cache.requested},
                    {"bricks_produced", f.cache.produced},
                    {"bricks_empty", f.cache.empty},
                    {"bricks_clear", f.cache.clear},
                    {"bricks_marked_empty", f.cache.marked},
                    {"bricks_failed", f.cache.failed},
                    {"bricks_unsampled", f.cache.unsampled},
                    {"evictions", f.cache.evicted},
                    {"pool_occupancy", f.cache.resident},
                    {"samples", f.cache.samples},
                    {"brick_lookups", f.cache.lookups},
                    {"empty_skips", f.cache.skips},
                    {"coarser_pixels", f.cache.coarser},
                    {"unfinished_pixels", f.unfinishedPixels},
                    {"launches", f.launches},
                    {"launch_failures", f.launchFailures},
                    {"deferred_productions", f.deferred},
                    {"swept_pixels", f.sweptPixels},
                    {"relaunched_rays", f.relaunchedRays},
                    {"longest_wait_list", f.longestWaitList},
                    {"spike", f.spike},
                    {"lookahead_claims", f.lookaheadClaims},
                    {"prefetch_claims", f.prefetchClaims},
                    {"prefetch_rays", f.prefetchRays},
                    {"prefetch_entered", f.prefetchEntered},
                    {"prefetch_items", f.prefetchItems},
                    {"bricks_prefetched", f.cache.prefetched},
                    {"prefetched_unused", f.cache.prefetchUnused},
                    {"tiles", f.tiles},
                    {"tile_splits", f.tileSplits},
                    {"tile_plans", f.tilePlans},
                    {"plan_ms", f.planMs},
                    {"lod_bias", f.lodBias},
                    {"degraded", f.degraded}});
  for (size_t i = 0; i < costs.size(); ++i)
    list[i]["ray_costs"] = {{"lookups", quantilesJson(costs[i].lookups)},
                            {"samples", quantilesJson(costs[i].samples)},
                            {"stops", quantilesJson(costs[i].stops)}};
  j["frames"] = list;
  return j.dump(1);
}

void writeStatsJson(const std::string& path, const SequenceOptions& o,
                    const std::vector<FrameStats>& frames, const MemoryReport& memory,
                    const std::vector<RayCostSummary>& costs) {
  std::ofstream out(path);
  GVDP_INPUT_CHECK(out.good(), "cannot write '", path, "'");
  out << statsJson(o, frames, memory, costs) << "\n";
  GVDP_INPUT_CHECK(out.good(), "cannot write '", path, "'");
}

}  // namespace gvdp::detail
