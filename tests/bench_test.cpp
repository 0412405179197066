#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "gvdp/bench/bench.h"
#include "gvdp/bench/frame_stats.h"
#include "test_util.h"

namespace gvdp::detail {

TEST(FrameStats, OnePercentLowAndPercentilesOnSyntheticTimes) {
  // 200 frames: 198 at 10 ms, two at 50 ms. 1% of 200 = the 2 slowest.
  std::vector<double> ms(198, 10.0);
  ms.push_back(50.0);
  ms.push_back(50.0);
  FrameTimeStats s = frameTimeStats(ms);
  EXPECT_DOUBLE_EQ(s.avgFps, 1000.0 * 200 / (198 * 10.0 + 100.0));
  EXPECT_DOUBLE_EQ(s.low1Fps, 20.0);  // mean of the slowest 1%: 50 ms
  EXPECT_DOUBLE_EQ(s.medianMs, 10.0);
  EXPECT_DOUBLE_EQ(s.p99Ms, 10.0);  // nearest rank: the 198th of 200 sorted values
  ms[0] = 50.0;                     // now the 198th is a slow one
  EXPECT_DOUBLE_EQ(frameTimeStats(ms).p99Ms, 50.0);
  // Fewer than 100 frames: the 1% low is the slowest frame.
  FrameTimeStats few = frameTimeStats({4.0, 8.0, 5.0});
  EXPECT_DOUBLE_EQ(few.low1Fps, 125.0);
  EXPECT_DOUBLE_EQ(few.medianMs, 5.0);
}

// The slowest frame and its bricks over the mean: a spike of the path shows as a ratio above 1.
TEST(FrameStats, SlowestFrameAndItsBricksOverTheMean) {
  SlowestFrame s = slowestFrame({2.0, 9.0, 3.0, 2.5}, {100, 700, 100, 100});
  EXPECT_EQ(s.index, 1u);
  EXPECT_DOUBLE_EQ(s.bricksOverMean, 700.0 / 250.0);
  s = slowestFrame({2.0, 2.0, 6.0}, {0, 0, 0});
  EXPECT_EQ(s.index, 2u);
  EXPECT_DOUBLE_EQ(s.bricksOverMean, 0.0) << "no bricks: no ratio";
  EXPECT_EQ(slowestFrame({}, {}).index, 0u);
  EXPECT_DOUBLE_EQ(slowestFrame({1.0}, {}).bricksOverMean, 0.0) << "sizes differ: nothing";
}

// The slowest frame's time over the time the other frames' line (ms against bricks) predicts for
// its bricks: 1 for a spike of work, more for a frame slower than its bricks explain.
TEST(FrameStats, SlowestFrameOverWhatTheOtherFramesPredict) {
  // The others lie on ms = 1 + 0.01 bricks; the slowest too (a spike of work): 1.
  SlowestFrame s = slowestFrame({2.0, 3.0, 11.0, 2.5}, {100, 200, 1000, 150});
  EXPECT_EQ(s.index, 2u);
  EXPECT_NEAR(s.overPredicted, 1.0, 1e-12);
  // The same bricks but twice the time the line predicts: a latency.
  EXPECT_NEAR(slowestFrame({2.0, 3.0, 22.0, 2.5}, {100, 200, 1000, 150}).overPredicted, 2.0, 1e-12);
  // Bricks that do not vary: the prediction is the others' mean time.
  EXPECT_NEAR(slowestFrame({2.0, 6.0, 4.0}, {50, 50, 50}).overPredicted, 2.0, 1e-12);
  // Fewer bricks taking longer among the others: the slope is held at 0, the mean again.
  EXPECT_NEAR(slowestFrame({3.0, 9.0, 1.0}, {0, 80, 100}).overPredicted, 9.0 / 2.0, 1e-12);
  EXPECT_EQ(slowestFrame({2.0, 9.0}, {1, 5}).overPredicted, 0.0) << "under 3 frames: no line";
}

TEST(Bench, ResultsJsonHasTheSchemaAndSpeedupsAgainstSp) {
  BenchOptions o;
  o.scenes = {"aligned-spheres"};
  o.movements = {Movement::Walkthrough, Movement::Sideways};
  o.schedulers = {SchedulerKind::Sp, SchedulerKind::Dp};
  o.width = 32;
  o.height = 20;
  o.frames = 2;
  o.warmup = 1;
  int calls = 0;
  BenchResults r = runBench(o, [&](int done, int total, const std::string&) {
    ++calls;
    EXPECT_LE(done, total);
  });
  EXPECT_EQ(calls, 4);
  nlohmann::json j = nlohmann::json::parse(benchJson(r));
  for (const char* key : {"device", "backend", "width", "height", "frames", "cells"})
    EXPECT_TRUE(j.contains(key)) << key;
  // pt's settings, as the options gave them (the defaults here).
  EXPECT_EQ(j["lookahead"], DEFAULT_LOOKAHEAD);
  EXPECT_EQ(j["tail_lookahead"], DEFAULT_TAIL_LOOKAHEAD);
  EXPECT_EQ(j["prefetch"], DEFAULT_PREFETCH);
  EXPECT_EQ(j["far_prefetch"], 0);
  ASSERT_EQ(j["cells"].size(), 4u);
  for (const auto& c : j["cells"]) {
    for (const char* key : {"scene", "movement", "scheduler", "avg_fps", "low1_fps", "median_ms",
                            "p99_ms", "bricks_per_frame", "unfinished_pixels", "speedup_vs_sp"})
      EXPECT_TRUE(c.contains(key)) << key;
    EXPECT_EQ(c["unfinished_pixels"], 0);
    EXPECT_GT(c["avg_fps"].get<double>(), 0.0);
    EXPECT_EQ(c["frame_ms"].size(), 2u);
    EXPECT_EQ(c["frame_bricks"].size(), 2u);
    int slowest = c["slowest_frame"].get<int>();
    EXPECT_TRUE(slowest == 1 || slowest == 2) << "a measured frame, counted from the path's start";
    EXPECT_GE(c["slowest_bricks_x"].get<double>(), 0.0);
    EXPECT_LE(c["slowest_bricks_x"].get<double>(), 2.0)
        << "one of two frames: at most twice the mean";
    EXPECT_EQ(c["slowest_over_predicted"].get<double>(), 0.0) << "two frames: no line to predict";
    EXPECT_GT(c["first_ms"].get<double>(), 0.0) << "frame 0, a warm-up frame, is timed too";
    if (c["scheduler"] == "sp") {
      EXPECT_DOUBLE_EQ(c["speedup_vs_sp"].get<double>(), 1.0);
    }
  }
  std::string md = benchMarkdown(r);
  EXPECT_NE(md.find("| walkthrough |"), std::string::npos);
  EXPECT_NE(md.find("aligned-spheres SU dp"), std::string::npos);
  EXPECT_NE(benchCsv(r).find("aligned-spheres,sideways,dp,"), std::string::npos);
  EXPECT_NE(benchCsv(r).find(",slowest_frame,slowest_bricks_x,slowest_over_predicted,first_ms\n"),
            std::string::npos);
}

TEST(Bench, CommandWritesItsOutputsAndRejectsBadLists) {
  std::string dir = test::tempDir("bench");
  std::filesystem::create_directories(dir);
  test::CommandResult r = test::runGvdp(
      "bench --backend cpu --scenes perlin --movements spinning --schedulers sp --frames 1 "
      "--warmup 0 --width 32 --height 20 --out " +
      dir + "/r.json --markdown " + dir + "/r.md");
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(dir + "/r.json");
  EXPECT_EQ(nlohmann::json::parse(in)["cells"].size(), 1u);
  EXPECT_TRUE(std::filesystem::exists(dir + "/r.md"));
  EXPECT_EQ(test::runGvdp("bench --backend cpu --scenes moon --out " + dir + "/x.json").status, 2);
  EXPECT_EQ(
      test::runGvdp("bench --backend cpu --schedulers direct --out " + dir + "/x.json").status, 2);
  EXPECT_EQ(test::runGvdp("bench --backend cpu --schedulers graph --out " + dir + "/x.json").status,
            2);
  std::filesystem::remove_all(dir);
}

}  // namespace gvdp::detail
