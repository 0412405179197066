// Helpers shared by the tests: running the gvdp binary, skipping GPU tests without a device.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "gvdp/base/gpu.h"
#include "gvdp/bench/sequence.h"
#include "gvdp/sched/builtin_producer.h"

namespace gvdp::detail::test {

struct CommandResult {
  int status;
  std::string output;  // stdout and stderr together
};

// The scheduler of a sequence's options over its built-in scene, for tests that drive frames
// (FrameSetup) themselves.
inline std::unique_ptr<Scheduler> schedulerFor(const SequenceOptions& o) {
  return makeScheduler(o.scheduler, builtinProducerKernels(findScene(o.scene).world));
}

// The gvdp binary under test: $GVDP_BIN when set, else the one built beside the tests, else (tests
// carried to another machine without their build folder, scripts/carry.sh) the gvdp in the test
// binary's own folder. None there: the build's path, whose runs then fail naming it.
inline std::string gvdpBinary() {
  if (const char* env = std::getenv("GVDP_BIN")) return env;
  std::error_code ec;
  if (std::filesystem::exists(GVDP_BINARY, ec)) return GVDP_BINARY;
  std::filesystem::path beside = std::filesystem::read_symlink("/proc/self/exe", ec);
  beside = beside.parent_path() / "gvdp";
  return !ec && std::filesystem::exists(beside, ec) ? beside.string() : GVDP_BINARY;
}

// A shell command's exit status and output (stdout and stderr together).
inline CommandResult runCommand(const std::string& command) {
  std::string cmd = command + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

inline CommandResult runGvdp(const std::string& args) {
  return runCommand(gvdpBinary() + " " + args);
}

// An environment variable as it was before a test changed it (set, or unset), put back when the
// guard goes out of scope, a failed assertion's return included.
class EnvRestore {
 public:
  explicit EnvRestore(const char* name) : name_(name) {
    const char* v = std::getenv(name);
    was_ = v != nullptr;
    if (was_) value_ = v;
  }
  EnvRestore(const EnvRestore&) = delete;
  EnvRestore& operator=(const EnvRestore&) = delete;
  ~EnvRestore() {
    if (was_)
      setenv(name_.c_str(), value_.c_str(), 1);
    else
      unsetenv(name_.c_str());
  }

 private:
  std::string name_, value_;
  bool was_ = false;
};

inline std::string tempDir(const std::string& name) {
  return ::testing::TempDir() + "gvdp_" + name + "_" + std::to_string(::getpid());
}

// Every frame of a sequence, images and stats.
struct Renders {
  std::vector<Image> images;
  std::vector<FrameStats> stats;
};

// Every frame of a sequence's options (a mesh world's too).
inline Renders renderRun(const SequenceOptions& o) {
  Renders r;
  renderSequence(o, [&](const Image& im, const FrameStats& st) {
    r.images.push_back(im);
    r.stats.push_back(st);
  });
  return r;
}

inline Renders renderRun(const std::string& scene, SchedulerOptions s, int frames, int w, int h,
                         Movement movement = Movement::Walkthrough, TileOptions tiles = {}) {
  SequenceOptions o;
  o.scene = scene;
  o.frames = frames;
  o.width = w;
  o.height = h;
  o.movement = movement;
  o.scheduler = s;
  o.tiles = tiles;
  return renderRun(o);
}

// The same frames rendered by the scheduler alone (no tiles, no retries): its own degraded
// frames when the pool is too small.
inline Renders schedulerRun(const std::string& scene, SchedulerOptions s, int frames, int w,
                            int h) {
  SequenceOptions o;
  o.scene = scene;
  o.width = w;
  o.height = h;
  o.scheduler = s;
  std::unique_ptr<Scheduler> scheduler = schedulerFor(o);
  Renders r;
  for (int f = 0; f < frames; ++f) {
    r.images.emplace_back();
    r.stats.push_back(scheduler->render(frameOf(o, f), r.images.back()));
  }
  return r;
}

inline std::string sceneName(int i) {
  return std::string(allScenes()[i].name);
}

}  // namespace gvdp::detail::test

#define GVDP_REQUIRE_GPU()                                 \
  do {                                                     \
    if (!::gvdp::detail::cudaDeviceAvailable())            \
      GTEST_SKIP() << ::gvdp::detail::cudaDeviceSummary(); \
  } while (0)
