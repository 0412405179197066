// Each pixel's brick lookups, samples and stops (FrameStats::rayCosts, `gvdp render --cost-map`):
// on every cached scheduler and both backends they add up to the frame's counts, tiles included,
// and every ray of sp's first frame (an empty cache) stops; the quantiles and the heat map read
// them right; the command writes the pictures and the summary (its refusal for `direct`:
// cli_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numeric>

#include "gvdp/io/draw.h"
#include "gvdp/io/png.h"
#include "gvdp/io/ray_cost_map.h"
#include "test_util.h"

namespace gvdp::detail {
namespace {

uint64_t sum(const std::vector<uint32_t>& v) {
  return std::accumulate(v.begin(), v.end(), uint64_t{0});
}

void expectCostsAddUp(Backend backend, SchedulerKind kind, TileOptions tiles = {}) {
  SchedulerOptions s{backend, kind};
  s.rayCosts = true;
  const int w = 96, h = 60;
  test::Renders r = test::renderRun("perlin", s, 3, w, h, Movement::Walkthrough, tiles);
  for (size_t f = 0; f < r.stats.size(); ++f) {
    const FrameStats& st = r.stats[f];
    const RayCosts& c = st.rayCosts;
    std::string what = std::string(schedulerName(kind)) + " on " +
                       std::string(backendName(backend)) + ", frame " + std::to_string(f) +
                       ", tiles " + std::to_string(st.tiles);
    ASSERT_EQ(c.width, w) << what;
    ASSERT_EQ(c.height, h) << what;
    ASSERT_EQ(c.lookups.size(), static_cast<size_t>(w * h)) << what;
    ASSERT_EQ(c.samples.size(), static_cast<size_t>(w * h)) << what;
    ASSERT_EQ(c.stops.size(), static_cast<size_t>(w * h)) << what;
    EXPECT_EQ(sum(c.lookups), st.cache.lookups) << what;
    EXPECT_EQ(sum(c.samples), st.cache.samples) << what;
    // Every ray decides at least its first brick; most of them sample something.
    EXPECT_GE(*std::min_element(c.lookups.begin(), c.lookups.end()), 1u) << what;
    EXPECT_GT(st.cache.samples, 0u) << what;
    // sp's first pass of a first frame finds every ray's first brick missing (dp and pt publish
    // bricks while rays run: a later ray may find its first brick resident).
    if (kind == SchedulerKind::Sp && f == 0 && st.tiles == 1) {
      EXPECT_GE(*std::min_element(c.stops.begin(), c.stops.end()), 1u) << what;
    }
    // pt: every relaunched ray had parked after a stop.
    if (kind == SchedulerKind::Pt) {
      EXPECT_GE(sum(c.stops), st.relaunchedRays) << what;
    }
  }
  // Rays stop less once the cache holds their bricks.
  EXPECT_LT(sum(r.stats.back().rayCosts.stops), sum(r.stats.front().rayCosts.stops));
}

}  // namespace

TEST(RayCosts, AddUpToTheFramesCountsOnTheCpu) {
  for (SchedulerKind k : {SchedulerKind::Sp, SchedulerKind::Dp, SchedulerKind::Pt})
    expectCostsAddUp(Backend::Cpu, k);
}

TEST(RayCosts, TilesPutTheirCostsWhereTheirPixelsAre) {
  TileOptions grid;
  grid.mode = TileOptions::Mode::Grid;
  grid.grid = 2;
  expectCostsAddUp(Backend::Cpu, SchedulerKind::Pt, grid);
}

TEST(RayCosts, AreRecordedOnlyWhenAsked) {
  test::Renders r = test::renderRun("perlin", {Backend::Cpu, SchedulerKind::Sp}, 1, 64, 40);
  EXPECT_TRUE(r.stats[0].rayCosts.empty());
  EXPECT_GT(r.stats[0].cache.lookups, 0u);
}

TEST(RayCostsGpu, AddUpToTheFramesCounts) {
  GVDP_REQUIRE_GPU();
  for (SchedulerKind k :
       {SchedulerKind::Sp, SchedulerKind::Dp, SchedulerKind::Pt, SchedulerKind::Graph})
    expectCostsAddUp(Backend::Cuda, k);
}

TEST(RayCosts, QuantilesAndHeatMap) {
  RayCosts c;
  c.width = 4;
  c.height = 2;
  c.lookups = {1, 2, 3, 4, 5, 6, 7, 100};  // the largest at (3, 1)
  c.samples = {0, 0, 0, 0, 0, 0, 9, 0};    // at (2, 1)
  c.stops = {0, 3, 0, 0, 0, 0, 0, 0};      // at (1, 0)
  RayCostSummary s = summarizeRayCosts(c);
  EXPECT_DOUBLE_EQ(s.lookups.mean, 128.0 / 8);
  EXPECT_EQ(s.lookups.p50, 4u);  // nearest rank: the 4th of 8
  EXPECT_EQ(s.lookups.p99, 100u);
  EXPECT_EQ(s.lookups.max, 100u);
  EXPECT_EQ(s.lookups.maxX, 3);
  EXPECT_EQ(s.lookups.maxY, 1);
  EXPECT_EQ(s.samples.p50, 0u);
  EXPECT_EQ(s.samples.maxX, 2);
  EXPECT_EQ(s.samples.maxY, 1);
  EXPECT_EQ(s.stops.max, 3u);
  EXPECT_EQ(s.stops.maxX, 1);
  EXPECT_EQ(s.stops.maxY, 0);
  Image im = rayCostImage(c, s, "test");
  // Each panel's largest value is the ramp's top, a zero its bottom; the map sits below the title
  // and labels, at the panels' left edges.
  auto colours = [&](uint32_t colour) {
    return std::count(im.pixels.begin(), im.pixels.end(), colour);
  };
  const uint32_t top = rgb(252, 255, 164), bottom = rgb(0, 0, 4);
  EXPECT_GE(colours(top), 3) << "a pixel of each panel at its maximum (and the bars)";
  EXPECT_GE(colours(bottom), 7 + 7) << "7 samples and 7 stops are 0";
  EXPECT_GT(im.width, 3 * c.width);
  EXPECT_GT(im.height, c.height);
}

TEST(RayCosts, CostMapCommandWritesPicturesAndQuantiles) {
  std::string dir = test::tempDir("cost_map");
  test::CommandResult r = test::runGvdp(
      "render --backend cpu --scheduler pt --frames 2 --width 64 --height 40 --cost-map --out " +
      dir);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("lookups per ray"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" ray_costs "), std::string::npos)
      << "in the memory report: " << r.output;
  for (const char* name : {"/cost_0000.png", "/cost_0001.png"}) {
    Image im = readPng(dir + name);
    EXPECT_GT(im.width, 3 * 64) << name;
    EXPECT_GT(im.height, 40) << name;
  }
  std::ifstream in(dir + "/stats.json");
  nlohmann::json j = nlohmann::json::parse(in);
  for (const nlohmann::json& f : j["frames"]) {
    const nlohmann::json& l = f["ray_costs"]["lookups"];
    EXPECT_GE(l["max"].get<uint32_t>(), l["p99"].get<uint32_t>());
    EXPECT_GE(l["p99"].get<uint32_t>(), l["p50"].get<uint32_t>());
    EXPECT_GE(l["p50"].get<uint32_t>(), 1u);
    EXPECT_NEAR(l["mean"].get<double>() * 64 * 40, f["brick_lookups"].get<double>(),
                1e-6 * 64 * 40 * l["mean"].get<double>());
    EXPECT_EQ(l["max_pixel"].size(), 2u);
    EXPECT_TRUE(f["ray_costs"]["samples"].contains("p999"));
    EXPECT_TRUE(f["ray_costs"]["stops"].contains("max"));
  }
  std::filesystem::remove_all(dir);
}

// The render-only frame's map beside its timeline (the frame whose longest warps the map explains).
TEST(RayCosts, TimelineWritesTheFramesCostMap) {
  std::string dir = test::tempDir("timeline_cost_map");
  std::filesystem::create_directories(dir);
  test::CommandResult r = test::runGvdp(
      "timeline --backend cpu --scheduler pt --frame 2 --again --width 64 --height 40 --out " +
      dir + "/t.png --cost-map " + dir + "/cost.png");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("lookups per ray"), std::string::npos) << r.output;
  Image im = readPng(dir + "/cost.png");
  EXPECT_GT(im.width, 3 * 64);
  std::filesystem::remove_all(dir);
  test::CommandResult d = test::runGvdp(
      "timeline --backend cpu --scheduler direct --frame 1 --width 32 --height 20 --out " + dir +
      "/t.png --cost-map " + dir + "/cost.png");
  EXPECT_EQ(d.status, 2) << d.output;
  EXPECT_NE(d.output.find("--cost-map"), std::string::npos) << d.output;
}

}  // namespace gvdp::detail
