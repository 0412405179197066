#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "gvdp/base/parallel.h"
#include "gvdp/bench/sequence.h"
#include "gvdp/io/timeline_export.h"
#include "gvdp/profile/frame_timeline.h"
#include "gvdp/profile/timeline_cpu.h"
#include "test_util.h"

namespace gvdp::detail {

namespace {
TimelineRecord rec(uint64_t a, uint64_t b, int lane, TaskKind k) {
  return {a, b, static_cast<uint16_t>(lane), static_cast<uint16_t>(lane), k};
}

FrameStats recordedFrame(Backend backend, SchedulerKind kind, int frame) {
  SequenceOptions o;
  o.scene = "perlin";
  o.width = 64;
  o.height = 40;
  o.frames = frame + 1;
  o.scheduler = {backend, kind};
  o.scheduler.timeline = true;
  FrameStats last;
  renderSequence(o, [&](const Image&, const FrameStats& s) { last = s; });
  return last;
}

void expectWellFormed(const TimelineCapture& t, bool cpu) {
  ASSERT_GT(t.records.size(), 0u);
  EXPECT_EQ(t.overflow, 0u);
  std::map<int, std::vector<std::pair<uint64_t, uint64_t>>> perLane;
  for (const TimelineRecord& r : t.records) {
    EXPECT_LE(r.start, r.end);
    EXPECT_LT(r.smStart, t.lanes);
    EXPECT_EQ(r.smStart, r.smEnd) << "a block never migrates";
    EXPECT_LT(static_cast<int>(r.kind), TASK_KIND_COUNT);
    perLane[r.smStart].push_back({r.start, r.end});
  }
  if (!cpu) return;
  // One CPU worker runs one task at a time.
  for (auto& [lane, v] : perLane) {
    std::sort(v.begin(), v.end());
    for (size_t i = 1; i < v.size(); ++i) EXPECT_LE(v[i - 1].second, v[i].first) << "lane " << lane;
  }
}
}  // namespace

TEST(Timeline, StatisticsAreExactOnSyntheticRecords) {
  // Lane 0: render [0, 10] and production [5, 15]; lane 1: render [0, 4]; lanes 2, 3 idle.
  std::vector<TimelineRecord> r = {rec(1000, 1010, 0, TaskKind::Render),
                                   rec(1005, 1015, 0, TaskKind::Produce),
                                   rec(1000, 1004, 1, TaskKind::Render)};
  TimelineStats s = timelineStats(r, 2);
  EXPECT_DOUBLE_EQ(s.spanMs, 15e-6);
  EXPECT_DOUBLE_EQ(s.busyFraction[0], 14.0 / 30.0);
  EXPECT_DOUBLE_EQ(s.busyFraction[1], 10.0 / 30.0);
  EXPECT_DOUBLE_EQ(s.idleFraction, 1.0 - 19.0 / 30.0);
  EXPECT_DOUBLE_EQ(s.tailMs, 0.0);  // lane 0 alone is half of 2 lanes, busy to the end
  TimelineStats four = timelineStats(r, 4);
  // Half of 4 lanes = 2 busy lanes: true on [0, 4] only, so the tail is 15 - 4.
  EXPECT_DOUBLE_EQ(four.tailMs, 11e-6);
  EXPECT_DOUBLE_EQ(four.idleFraction, 1.0 - 19.0 / 60.0);
}

TEST(Timeline, BufferCountsOverflowAndNeverWritesPastIt) {
  CpuTimeline t(2);
  t.begin();
  for (int i = 0; i < 5; ++i) t.view().push(rec(i, i + 1, 0, TaskKind::Render));
  uint64_t overflow = 0;
  std::vector<TimelineRecord> r = t.end(&overflow);
  EXPECT_EQ(r.size(), 2u);
  EXPECT_EQ(overflow, 3u);
}

TEST(Timeline, ChromeTraceHasTheTraceEventFields) {
  std::vector<TimelineRecord> r = {rec(2000, 5000, 1, TaskKind::Produce)};
  nlohmann::json j = nlohmann::json::parse(chromeTraceJson(r, 2));
  const auto& events = j["traceEvents"];
  ASSERT_EQ(events.size(), 3u);  // 2 track names + 1 task
  const auto& e = events[2];
  EXPECT_EQ(e["ph"], "X");
  EXPECT_EQ(e["name"], "production");
  EXPECT_EQ(e["tid"], 1);
  EXPECT_DOUBLE_EQ(e["ts"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(e["dur"].get<double>(), 3.0);  // microseconds
  EXPECT_EQ(events[0]["ph"], "M");
}

TEST(Timeline, PictureShowsKindsInTheirColoursAndIdleInBlack) {
  std::vector<TimelineRecord> r = {rec(0, 1000, 0, TaskKind::Render),
                                   rec(500, 1000, 1, TaskKind::Produce)};
  Image im = timelineImage(r, 2, "test");
  int cell = 1200 / 2;
  EXPECT_EQ(im.width, 70 + 2 * cell + 20);
  EXPECT_EQ(im.height, 46 + 900 + 30);
  auto at = [&](int lane, double frac) {
    int y = 46 + static_cast<int>(frac * 899);
    return im.pixels[static_cast<size_t>(y) * im.width + 70 + lane * cell + cell / 2];
  };
  EXPECT_EQ(at(0, 0.2), 0xff2828dcu);  // red: render
  EXPECT_EQ(at(1, 0.2), 0xff000000u);  // black: lane 1 idle before 500 ns
  EXPECT_EQ(at(1, 0.8), 0xffe65a32u);  // blue: production
}

// The thread pool is shared: a CPU timeline records the runs of the thread recording it, not
// another thread's (two renderers on two threads), which would also push into it while its
// capture ends (a data race ThreadSanitizer once found in CI, between the serve loop's timeline and
// another test's renders).
// Two threads record two timelines on the shared pool at once (the viewer's render loop and a
// renderer on another thread; CI's TSan found a worker pushing one thread's records into the
// other's timeline while it was being read): each timeline holds its own thread's runs only.
TEST(ThreadPool, ATimelineRecordsOnlyTheRunsOfItsOwnThread) {
  auto recordRuns = [](TaskKind kind) {
    // One timeline per thread, as a renderer keeps one (a fresh one per frame is a large
    // allocation, which took ThreadSanitizer seconds each).
    std::unique_ptr<FrameTimeline> t = makeCpuFrameTimeline();
    for (int k = 0; k < 50; ++k) {
      t->begin();
      for (int r = 0; r < 4; ++r)
        parallelFor(
            1000, [](int64_t) {}, 8, static_cast<uint8_t>(kind));
      TimelineCapture c = t->end();
      EXPECT_FALSE(c.records.empty());
      for (const TimelineRecord& rec : c.records) EXPECT_EQ(rec.kind, kind);
    }
  };
  std::atomic<bool> stop{false};
  std::thread unrecorded([&] {
    while (!stop) {
      parallelFor(
          1000, [](int64_t) {}, 8, static_cast<uint8_t>(TaskKind::Cache));
      std::this_thread::sleep_for(std::chrono::microseconds(200));  // leaves the others turns
    }
  });
  std::thread other([&] { recordRuns(TaskKind::Sweep); });
  recordRuns(TaskKind::Render);
  other.join();
  stop = true;
  unrecorded.join();
}

TEST(Timeline, CpuRecordsAreWellFormedForSpAndDp) {
  FrameStats sp = recordedFrame(Backend::Cpu, SchedulerKind::Sp, 1);
  expectWellFormed(sp.timeline, true);
  FrameStats dp = recordedFrame(Backend::Cpu, SchedulerKind::Dp, 1);
  expectWellFormed(dp.timeline, true);
  TimelineStats s = timelineStats(dp.timeline.records, dp.timeline.lanes);
  EXPECT_GT(s.busyFraction[static_cast<int>(TaskKind::Render)], 0.0);
}

TEST(Timeline, GpuRecordsAreWellFormedForSpAndDp) {
  GVDP_REQUIRE_GPU();
  for (SchedulerKind k : {SchedulerKind::Sp, SchedulerKind::Dp}) {
    FrameStats f = recordedFrame(Backend::Cuda, k, 2);
    expectWellFormed(f.timeline, false);
    TimelineStats s = timelineStats(f.timeline.records, f.timeline.lanes);
    std::printf("[ measure ] %s 64x40 frame 2: %s\n", std::string(schedulerName(k)).c_str(),
                timelineSummary(s).c_str());
  }
}

// `timeline --again`'s sequence: the last pose once more, from the cache its frame filled - the
// render-only floor: the same image, bit for bit, and not one brick produced.
TEST(Sequence, AgainRendersTheLastPoseFromTheCacheItFilled) {
  for (SchedulerKind kind : {SchedulerKind::Sp, SchedulerKind::Pt}) {
    SequenceOptions o;
    o.scene = "random-spheres";
    o.width = 64;
    o.height = 40;
    o.frames = 3;
    o.again = 1;
    o.scheduler = {Backend::Cpu, kind};
    std::vector<Image> images;
    std::vector<FrameStats> stats;
    renderSequence(o, [&](const Image& im, const FrameStats& s) {
      images.push_back(im);
      stats.push_back(s);
    });
    ASSERT_EQ(images.size(), 4u);
    EXPECT_GT(stats[2].cache.produced, 0u) << "the last pose's frame produced bricks";
    EXPECT_EQ(stats[3].cache.produced, 0u) << schedulerName(kind);
    EXPECT_EQ(images[3].pixels, images[2].pixels) << schedulerName(kind);
    EXPECT_EQ(stats[3].unfinishedPixels, 0);
  }
  SequenceOptions bad;
  bad.again = -1;
  EXPECT_THROW(validate(bad), InputError);
}

}  // namespace gvdp::detail
