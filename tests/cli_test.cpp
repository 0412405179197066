#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "test_util.h"

namespace gvdp {

namespace {
void expectInputError(const std::string& args, const std::string& mentions) {
  test::CommandResult r = test::runGvdp(args);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
  EXPECT_NE(r.output.find("gvdp: error:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(mentions), std::string::npos) << args << "\n" << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << "one line: " << r.output;
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
  expectInputError("render --backend cpu --width 16000 --height 16000" + out, "16000x16000");
  expectInputError("render --backend cpu --frames 0" + out, "--frames 0");
  expectInputError("render --backend cpu --width abc" + out, "abc");
  expectInputError("render --backend cpu --origin 1,2" + out, "'1,2'");
  expectInputError("render --backend cpu --levels 40" + out, "--levels 40");
  expectInputError("render --backend cpu --bogus 3" + out, "--bogus");
  expectInputError("render --backend cpu --out /proc/gvdp_cannot_be_here",
                   "/proc/gvdp_cannot_be_here");
  expectInputError("frobnicate", "frobnicate");
  expectInputError("render --backend cpu --scheduler graph" + out, "'graph'");
}

TEST(Cli, PtRenderReportsItsTasksInStats) {
  std::string dir = test::tempDir("cli_pt");
  test::CommandResult r = test::runGvdp(
      "render --backend cpu --scheduler pt --scene perlin --width 40 --height 24 --frames 1 "
      "--out " +
      dir);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("relaunched rays"), std::string::npos) << r.output;
  std::ifstream in(dir + "/stats.json");
  nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_GT(j["frames"][0]["launches"].get<int>(), 0);
  EXPECT_EQ(j["frames"][0]["unfinished_pixels"], 0);
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
  std::ifstream in(dir + "/stats.json");
  nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j["frames"].size(), 2u);
  EXPECT_EQ(j["frames"][1]["index"], 1);
  EXPECT_GT(j["frames"][0]["ms"].get<double>(), 0.0);
  EXPECT_EQ(j["frames"][0]["unfinished_pixels"], 0);
  EXPECT_EQ(j["scene"], "aligned-spheres");
  EXPECT_NE(r.output.find("FPS"), std::string::npos);
  std::filesystem::remove_all(dir);
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

}  // namespace gvdp
