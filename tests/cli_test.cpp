#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "gvdp/base/error.h"
#include "gvdp/io/video.h"
#include "gvdp/sched/graph/graph.h"
#include "gvdp/sched/pt/pt.h"
#include "test_util.h"

namespace gvdp::detail {

namespace {
void expectInputError(const std::string& args, const std::string& mentions) {
  test::CommandResult r = test::runGvdp(args);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
  EXPECT_NE(r.output.find("gvdp: error:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(mentions), std::string::npos) << args << "\n" << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << "one line: " << r.output;
}

// Small and fast: what these commands would render if they were not refused.
const std::string TINY = " --width 32 --height 20 --frames 1";
const std::string TINY_BENCH =
    " --backend cpu --scenes perlin --movements forward --schedulers sp --frames 1 --warmup 0";

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

nlohmann::json readStats(const std::string& dir) {
  std::ifstream in(dir + "/stats.json");
  return nlohmann::json::parse(in);
}

uint64_t physicalMemoryBytes() {
  return static_cast<uint64_t>(sysconf(_SC_PHYS_PAGES)) *
         static_cast<uint64_t>(sysconf(_SC_PAGESIZE));
}
}  // namespace

TEST(Cli, BadInputIsOneLineNamingTheValueWithStatus2) {
  std::string out = " --out " + test::tempDir("cli_bad");
  expectInputError("render --backend cpu --scene moon" + out, "'moon'");
  expectInputError("render --backend cpu --movement moonwalk" + out, "'moonwalk'");
  expectInputError("render --backend gpu" + out, "'gpu'");
  expectInputError("render --backend cpu --scheduler magic" + out, "'magic'");
  expectInputError("render --backend cpu --width 0" + out, "--width 0");
  expectInputError("render --backend cpu --width -5" + out, "-5");
  expectInputError("render --backend cpu --height 100000" + out, "--height 100000");
  expectInputError("render --backend cpu --width 30000 --height 30000" + out, "30000x30000");
  expectInputError("render --backend cpu --tiles 0" + out, "--tiles '0'");
  expectInputError("render --backend cpu --tiles lots" + out, "--tiles 'lots'");
  expectInputError("render --backend cpu --scheduler direct --cost-map" + out, "--cost-map");
  expectInputError("render --backend cpu --tiles 257" + out, "--tiles '257'");
  expectInputError("render --backend cpu --tiles off --width 4096 --height 4096" + out,
                   "4096x4096 for --tiles off");
  expectInputError("render --backend cpu --frames 0" + out, "--frames 0");
  expectInputError("render --backend cpu --width abc" + out, "abc");
  expectInputError("render --backend cpu --origin 1,2" + out, "'1,2'");
  expectInputError("render --backend cpu --levels 40" + out, "--levels 40");
  expectInputError("render --backend cpu --bogus 3" + out, "--bogus");
  expectInputError("render --backend cpu --out /proc/gvdp_cannot_be_here",
                   "/proc/gvdp_cannot_be_here");
  expectInputError("frobnicate", "frobnicate");
  expectInputError("render --backend cpu --scheduler graph" + out, "'graph'");
  expectInputError("render --backend cpu --width -2147483648" + out, "--width -2147483648");
}

// Ranges are checked on the user's number before any arithmetic on it (9e12 MiB overflowed a
// signed multiplication; UBSan in scripts/asan.sh).
TEST(Cli, PoolSizesOutOfRangeAreRefusedBeforeAnyArithmetic) {
  std::string out = " --out " + test::tempDir("cli_pool_range");
  expectInputError("render --backend cpu --pool-mb 9000000000000" + out,
                   "--pool-mb 9000000000000 (expected 1..190000)");
  expectInputError("render --backend cpu --pool-mb 0" + out, "--pool-mb 0");
  expectInputError("render --backend cpu --pool-mb -3" + out, "--pool-mb -3");
  expectInputError("render --backend cpu --pool-mb 190001" + out, "--pool-mb 190001");
  expectInputError("render --backend cpu --pool-bricks 9000000000000000000" + out,
                   "--pool-bricks 9000000000000000000 (expected 1..50000000)");
  expectInputError("render --backend cpu --pending-launches 9000000000000 --scheduler dp" + out,
                   "--pending-launches 9000000000000");
  expectInputError("bench" + TINY_BENCH + " --pool-bricks 0" + out, "--pool-bricks 0");
  expectInputError("render --backend cpu --lookahead 65 --scheduler pt" + out,
                   "bad --lookahead 65 (expected 0..64)");
  expectInputError("render --backend cpu --tail-lookahead 65 --scheduler pt" + out,
                   "bad --tail-lookahead 65 (expected 0..64)");
  expectInputError("bench" + TINY_BENCH + " --tail-lookahead -3" + out, "bad --tail-lookahead -3");
  expectInputError("render --backend cpu --lookahead -1 --scheduler pt" + out, "--lookahead -1");
  expectInputError("bench" + TINY_BENCH + " --lookahead 9000000000000" + out,
                   "--lookahead 9000000000000");
  expectInputError("render --backend cpu --prefetch 65 --scheduler pt" + out,
                   "bad --prefetch 65 (expected 0..64)");
  expectInputError("bench" + TINY_BENCH + " --prefetch -2" + out, "bad --prefetch -2");
  expectInputError("render --backend cpu --budget-ms -1" + out, "bad --budget-ms -1");
  expectInputError("render --backend cpu --budget-ms 60001" + out,
                   "bad --budget-ms 60001 (expected 0..60000)");
  expectInputError("render --backend cpu --budget-ms nan" + out, "--budget-ms");
  expectInputError("render --backend cpu --budget-ms 8ms" + out, "8ms");
  expectInputError("bench" + TINY_BENCH + " --budget-ms -0.5" + out, "bad --budget-ms -0.5");
}

// A pool inside the accepted range but larger than the machine: one line saying how much it
// needs and how much there is, before anything is allocated or written (was: bad_alloc, status 1).
TEST(Cli, PoolLargerThanTheMachineIsRefusedWithWhatItNeeds) {
  uint64_t mb = physicalMemoryBytes() / (1 << 20) + 1024;
  if (mb > 190000) GTEST_SKIP() << "this machine holds the largest accepted pool";
  std::string dir = test::tempDir("cli_pool_memory");
  std::string pool = "--pool-mb " + std::to_string(mb);
  expectInputError("render --backend cpu " + pool + TINY + " --out " + dir,
                   pool + " (scheduler sp at 32x20) needs ");
  expectInputError("render --backend cpu --scheduler pt " + pool + TINY + " --out " + dir,
                   "on the cpu backend, which has ");
  EXPECT_FALSE(std::filesystem::exists(dir));
  std::string bricks = std::to_string(physicalMemoryBytes() / 4000 + 1000);
  expectInputError("timeline --backend cpu --frame 0 --pool-bricks " + bricks +
                       " --width 32 --height 20 --out " + dir + "/t.png",
                   "--pool-bricks " + bricks);
  expectInputError("bench" + TINY_BENCH + " --pool-bricks " + bricks + " --out " + dir + "/r.json",
                   "a pool of " + bricks + " bricks needs ");
  EXPECT_FALSE(std::filesystem::exists(dir));
}

// Every output is checked before the first frame: nothing is rendered, nothing is left behind.
TEST(Cli, RenderRefusesAnUnwritableTimelineBeforeAnyFrame) {
  std::string dir = test::tempDir("cli_render_timeline");
  expectInputError("render --backend cpu" + TINY + " --out " + dir + " --timeline /proc/gvdp_x",
                   "'/proc/gvdp_x'");
  EXPECT_FALSE(std::filesystem::exists(dir + "/frame_0000.png"));
  EXPECT_FALSE(std::filesystem::exists(dir)) << "the out directory made for the check is removed";
}

TEST(Cli, RenderRefusesAnOutDirectoryItCannotWrite) {
  expectInputError("render --backend cpu" + TINY + " --out /proc", "output directory '/proc'");
  expectInputError("render --backend cpu" + TINY + " --out /proc/gvdp_x/y", "'/proc/gvdp_x/y'");
  std::string file = test::tempDir("cli_render_file");
  std::ofstream(file) << "a file";
  expectInputError("render --backend cpu" + TINY + " --out " + file, file);
  EXPECT_EQ(readFile(file), "a file");
  std::filesystem::remove(file);
}

TEST(Cli, TimelineRefusesUnwritableOutputsBeforeRendering) {
  std::string dir = test::tempDir("cli_timeline_out");
  std::filesystem::create_directories(dir);
  std::string args = "timeline --backend cpu --frame 0 --width 32 --height 20";
  expectInputError(args + " --out " + dir + "/t.png --trace /proc/gvdp_x.json",
                   "/proc/gvdp_x.json");
  expectInputError(args + " --out /proc/gvdp_x.png --trace " + dir + "/t.json", "/proc/gvdp_x.png");
  EXPECT_TRUE(std::filesystem::is_empty(dir)) << "no picture, no trace, no probe left";
  std::filesystem::remove_all(dir);
}

TEST(Cli, BenchRefusesUnwritableOutputsBeforeRunning) {
  std::string dir = test::tempDir("cli_bench_out");
  std::filesystem::create_directories(dir);
  std::string json = dir + "/r.json";
  std::ofstream(json) << "earlier results";
  std::string args = "bench" + TINY_BENCH + " --width 32 --height 20 --out " + json;
  expectInputError(args + " --csv /proc/gvdp_x.csv", "'/proc/gvdp_x.csv'");
  expectInputError(args + " --markdown /proc/gvdp_x.md", "'/proc/gvdp_x.md'");
  expectInputError(args + " --csv " + dir + "/r.csv --markdown /proc", "'/proc'");
  expectInputError("bench" + TINY_BENCH + " --out /proc/gvdp_x.json", "'/proc/gvdp_x.json'");
  EXPECT_EQ(readFile(json), "earlier results") << "a refused bench leaves earlier results alone";
  EXPECT_FALSE(std::filesystem::exists(dir + "/r.csv"));
  std::filesystem::remove_all(dir);
}

// Without a device, --backend cuda fails in one line before the banner and before any output.
TEST(Cli, CudaWithoutADeviceFailsBeforeTheBannerAndLeavesNoOutput) {
  if (cudaDeviceAvailable()) GTEST_SKIP() << "a CUDA device is present";
  std::string dir = test::tempDir("cli_no_cuda");
  expectInputError("render --backend cuda" + TINY + " --out " + dir, "backend 'cuda' unavailable");
  expectInputError("timeline --backend cuda --frame 0 --out " + dir + "/t.png",
                   "backend 'cuda' unavailable");
  expectInputError("bench --backend cuda --schedulers sp --out " + dir + "/r.json",
                   "backend 'cuda' unavailable");
  EXPECT_FALSE(std::filesystem::exists(dir));
}

// A flag the command or scheduler would ignore is refused, naming it.
TEST(Cli, FlagsACommandDoesNotUseAreRefused) {
  std::string dir = test::tempDir("cli_unused");
  std::string out = " --out " + dir;
  expectInputError("timeline --backend cpu --frame 0 --frames 3 --out " + dir + "/t.png",
                   "not --frames 3");
  expectInputError("timeline --backend cpu --frame 0 --frames 0 --out " + dir + "/t.png",
                   "not --frames 0");
  expectInputError("render --backend cpu --scheduler direct --pool-bricks 1000" + TINY + out,
                   "--pool-bricks 1000 is not used by scheduler direct");
  expectInputError("render --backend cpu --scheduler direct --pool-mb 64" + TINY + out,
                   "--pool-mb 64 is not used by scheduler direct");
  for (const char* scheduler : {"sp", "pt", "direct"})
    expectInputError(
        std::string("render --backend cpu --pending-launches 100 --scheduler ") + scheduler + TINY +
            out,
        std::string("--pending-launches 100 is used by scheduler dp only, not by ") + scheduler);
  for (const char* flag :
       {"--lookahead 4", "--tail-lookahead 8", "--prefetch 4", "--far-prefetch 8"})
    for (const char* scheduler : {"sp", "dp", "direct"})
      expectInputError(
          std::string("render --backend cpu ") + flag + " --scheduler " + scheduler + TINY + out,
          std::string(flag) + " is used by scheduler pt only, not by " + scheduler);
  expectInputError("render --backend cpu --scheduler direct --budget-ms 8" + TINY + out,
                   "--budget-ms 8 is not used by scheduler direct");
  expectInputError("timeline --backend cpu --frame 0 --scheduler pt --pending-launches 100 --out " +
                       dir + "/t.png",
                   "--pending-launches 100");
  std::string bench = "bench" + TINY_BENCH + " --out " + dir + "/r.json";
  expectInputError(bench + " --scale --width 320", "--width 320 is not used with --scale");
  expectInputError(bench + " --scale --height 200", "--height 200 is not used with --scale");
  std::string lists = "bench --backend cpu --frames 1 --warmup 0 --out " + dir + "/r.json";
  expectInputError(lists + " --schedulers sp,dp,sp", "--schedulers: 'sp' is listed twice");
  expectInputError(lists + " --scenes perlin,fbm,perlin", "--scenes: 'perlin' is listed twice");
  expectInputError(lists + " --movements forward,forward",
                   "--movements: 'forward' is listed twice");
  EXPECT_FALSE(std::filesystem::exists(dir));
}

TEST(Cli, PtRenderReportsItsTasksInStats) {
  std::string dir = test::tempDir("cli_pt");
  test::CommandResult r = test::runGvdp(
      "render --backend cpu --scheduler pt --scene perlin --width 40 --height 24 --frames 1 "
      "--out " +
      dir);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("relaunched rays"), std::string::npos) << r.output;
  nlohmann::json j = readStats(dir);
  EXPECT_GT(j["frames"][0]["launches"].get<int>(), 0);
  EXPECT_EQ(j["frames"][0]["unfinished_pixels"], 0);
  EXPECT_EQ(j["pool_bricks"], DEFAULT_POOL_BRICKS_CPU) << "the pool really used, not 0";
  EXPECT_FALSE(j.contains("pending_launches")) << "pt has no pending-launch buffer";
  std::filesystem::remove_all(dir);
}

// A budgeted render: every pixel finished, the pixels shown coarser counted per frame, the budget
// in stats.json and the frames within it printed.
TEST(Cli, BudgetedRenderReportsCoarserPixels) {
  std::string dir = test::tempDir("cli_budget");
  test::CommandResult r = test::runGvdp(
      "render --backend cpu --scheduler sp --scene perlin --width 40 --height 24 --frames 2 "
      "--budget-ms 0 --out " +
      dir);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("budget 0.00 ms: 0 of 2 frames within it"), std::string::npos)
      << r.output;
  nlohmann::json j = readStats(dir);
  EXPECT_EQ(j["budget_ms"], 0.0);
  EXPECT_GT(j["frames"][0]["coarser_pixels"].get<int>(), 0);
  EXPECT_EQ(j["frames"][0]["unfinished_pixels"], 0);
  std::filesystem::remove_all(dir);
}

// stats.json reports the configuration as used: dp's defaults resolved, --pool-mb in bricks; and
// where the frame's requested bricks went.
TEST(Cli, StatsReportTheResolvedConfiguration) {
  std::string dir = test::tempDir("cli_resolved");
  test::CommandResult r = test::runGvdp(
      "render --backend cpu --scheduler dp --scene perlin --width 32 --height 20 --frames 1 "
      "--pool-mb 64 --out " +
      dir);
  ASSERT_EQ(r.status, 0) << r.output;
  nlohmann::json j = readStats(dir);
  EXPECT_EQ(j["pool_bricks"], 64 * 1024 * 1024 / (BRICK_SAMPLE_COUNT * 4));
  EXPECT_EQ(j["pending_launches"], DEFAULT_PENDING_LAUNCHES);
  // Every brick requested ends produced (a slot), EMPTY, CLEAR (all zero, no slot) or failed;
  // perlin's first frame has CLEAR ones near its ground.
  const nlohmann::json& f = j["frames"][0];
  EXPECT_GT(f["bricks_clear"].get<int>(), 0);
  EXPECT_EQ(f["bricks_requested"].get<int>(),
            f["bricks_produced"].get<int>() + f["bricks_empty"].get<int>() +
                f["bricks_clear"].get<int>() + f["bricks_failed"].get<int>());
  std::filesystem::remove_all(dir);
}

TEST(Cli, RenderWritesFramesAndStats) {
  std::string dir = test::tempDir("cli_render");
  test::CommandResult r = test::runGvdp(
      "render --backend cpu --scheduler direct --scene aligned-spheres --width 32 --height 20 "
      "--frames 2 --out " +
      dir);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/frame_0000.png"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/frame_0001.png"));
  nlohmann::json j = readStats(dir);
  ASSERT_EQ(j["frames"].size(), 2u);
  EXPECT_EQ(j["frames"][1]["index"], 1);
  EXPECT_GT(j["frames"][0]["ms"].get<double>(), 0.0);
  EXPECT_EQ(j["frames"][0]["unfinished_pixels"], 0);
  EXPECT_EQ(j["scene"], "aligned-spheres");
  EXPECT_FALSE(j.contains("pool_bricks")) << "direct has no pool";
  EXPECT_NE(r.output.find("FPS"), std::string::npos);
  std::filesystem::remove_all(dir);
}

// --video: the frames through ffmpeg into an H.264 file with as many frames (ffprobe counts).
TEST(Cli, RenderEncodesAVideoWithFfmpeg) {
  if (findOnPath("ffmpeg").empty() || findOnPath("ffprobe").empty())
    GTEST_SKIP() << "no ffmpeg/ffprobe on the PATH (scripts/setup.sh installs ffmpeg)";
  std::string dir = test::tempDir("cli_video");
  test::CommandResult r = test::runGvdp(
      "render --backend cpu --scheduler sp --scene aligned-spheres --width 33 --height 21 "
      "--frames 5 --out " +
      dir + " --video " + dir + "/walk.mp4 --video-fps 24");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("(5 frames at 24 FPS)"), std::string::npos) << r.output;
  test::CommandResult probe = test::runCommand(
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
      "stream=codec_name,nb_read_frames,width,height -of csv=p=0 " +
      dir + "/walk.mp4");
  ASSERT_EQ(probe.status, 0) << probe.output;
  EXPECT_EQ(probe.output, "h264,34,22,5\n") << "odd sizes padded by a pixel";
  std::filesystem::remove_all(dir);
}

TEST(Cli, VideoWithoutFfmpegOrWithBadFlagsIsOneLine) {
  std::string dir = test::tempDir("cli_video_bad");
  test::CommandResult r =
      test::runCommand("env PATH=/nonexistent " + test::gvdpBinary() +
                       " render --backend cpu --out " + dir + " --video " + dir + "/x.mp4" + TINY);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("needs the ffmpeg command"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir)) << "refused before any output";
  expectInputError(
      "render --backend cpu --out " + dir + " --video " + dir + "/x.mp4 --video-fps 0" + TINY,
      "--video-fps 0");
  expectInputError("render --backend cpu --out " + dir + " --video /proc/nope/x.mp4" + TINY,
                   "/proc/nope/x.mp4");
}

TEST(Cli, ServeRefusesBadFlagsInOneLine) {
  expectInputError("serve --backend cpu --port 70000", "--port 70000");
  expectInputError("serve --backend cpu --port -1", "--port -1");
  expectInputError("serve --backend cpu --quality 0", "--quality 0");
  expectInputError("serve --backend cpu --scene moon", "'moon'");
  expectInputError("serve --backend cpu --scheduler direct", "'direct'");
  expectInputError("serve --backend cpu --scheduler graph", "'graph'");
  expectInputError("serve --backend cpu --width 100000", "'100000'");
  expectInputError("serve --backend cpu --budget-ms 5000", "budget");
  expectInputError("serve --backend cpu --pool-bricks 0", "--pool-bricks 0");
  expectInputError("serve --backend cpu --port 0 --host 256.0.0.1", "cannot listen on 256.0.0.1");
}

TEST(Cli, ScenesAndInfoList) {
  test::CommandResult scenes = test::runGvdp("scenes");
  EXPECT_EQ(scenes.status, 0);
  for (const char* n : {"perlin", "fbm", "forest", "random-spheres", "aligned-spheres"})
    EXPECT_NE(scenes.output.find(n), std::string::npos) << n;
  test::CommandResult info = test::runGvdp("info");
  EXPECT_EQ(info.status, 0);
  EXPECT_NE(info.output.find("cuda backend"), std::string::npos);
}

// GVDP_GRAPH_LOOP selects who repeats graph's loop (scripts/gpu_check.sh); a typo is an error.
TEST(Cli, GraphLoopEnvironmentIsCheckedByName) {
  test::EnvRestore restore("GVDP_GRAPH_LOOP");
  setenv("GVDP_GRAPH_LOOP", "hots", 1);
  EXPECT_THROW(graphDriverFromEnvironment(), InputError);
  setenv("GVDP_GRAPH_LOOP", "host", 1);
  EXPECT_EQ(graphDriverFromEnvironment(), GraphDriver::Host);
  unsetenv("GVDP_GRAPH_LOOP");
  EXPECT_EQ(graphDriverFromEnvironment(), GraphDriver::Device);
}

// GVDP_PT_PRODUCER_SHARE sets pt's producer SMs (unset: S = 2; 0: off); anything but an integer
// 0..4096 is an error.
TEST(Cli, PtProducerShareEnvironmentIsChecked) {
  test::EnvRestore restore("GVDP_PT_PRODUCER_SHARE");
  for (const char* bad : {"two", "-2", "4097", "2x", " 2"}) {
    setenv("GVDP_PT_PRODUCER_SHARE", bad, 1);
    EXPECT_THROW(ptProducerShareFromEnvironment(), InputError) << bad;
  }
  setenv("GVDP_PT_PRODUCER_SHARE", "5", 1);
  EXPECT_EQ(ptProducerShareFromEnvironment(), 5u);
  setenv("GVDP_PT_PRODUCER_SHARE", "0", 1);
  EXPECT_EQ(ptProducerShareFromEnvironment(), 0u);
  unsetenv("GVDP_PT_PRODUCER_SHARE");
  EXPECT_EQ(ptProducerShareFromEnvironment(), PT_PRODUCER_SHARE_DEFAULT);
  EXPECT_EQ(PT_PRODUCER_SHARE_DEFAULT, 2u);
  // Checked before the frame's work, by name, for pt only (the CPU ignores it).
  setenv("GVDP_PT_PRODUCER_SHARE", "two", 1);
  const std::string out = " --out " + test::tempDir("cli_producer_share");
  expectInputError("render --backend cpu --scheduler pt" + TINY + out,
                   "bad GVDP_PT_PRODUCER_SHARE 'two' (expected 0..4096; 0: off)");
}

// --far-prefetch N turns on pt's far prefetch (0: off, the default): 0..16 predicted frames, with
// the prefetch it extends (off by default, FAR_PREFETCH_STRIDE under a far prefetch unless
// --prefetch says); stats.json and the bench's JSON record both.
TEST(Cli, FarPrefetchIsCheckedAndRecorded) {
  const std::string dir = test::tempDir("cli_far"), out = " --out " + dir;
  expectInputError("render --backend cpu --scheduler pt --far-prefetch 17" + TINY + out,
                   "bad --far-prefetch 17 (expected 0..16 predicted frames; 0: off)");
  expectInputError("render --backend cpu --scheduler pt --far-prefetch -1" + TINY + out,
                   "bad --far-prefetch -1");
  expectInputError("render --backend cpu --scheduler pt --far-prefetch eight" + TINY + out,
                   "--far-prefetch");
  expectInputError("bench" + TINY_BENCH + " --far-prefetch 99" + out, "bad --far-prefetch 99");
  // (pt's only: Cli.FlagsACommandDoesNotUseAreRefused)
  expectInputError("render --backend cpu --scheduler pt --prefetch 0 --far-prefetch 8" + TINY + out,
                   "--far-prefetch 8 needs pt's prefetch, which --prefetch 0 turns off");
  test::CommandResult r =
      test::runGvdp("render --backend cpu --scheduler pt --far-prefetch 8" + TINY + out);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(readStats(dir)["far_prefetch"], 8);
  EXPECT_EQ(readStats(dir)["prefetch"], FAR_PREFETCH_STRIDE) << "the prefetch it extends, on";
  r = test::runGvdp("render --backend cpu --scheduler pt" + TINY + out);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(readStats(dir)["far_prefetch"], 0);
  EXPECT_EQ(readStats(dir)["prefetch"], DEFAULT_PREFETCH) << "off by default";
  std::filesystem::remove_all(dir);
}

}  // namespace gvdp::detail
