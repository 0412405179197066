// Helpers shared by the tests: running the gvdp binary, skipping GPU tests without a device.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "gvdp/base/gpu.h"

namespace gvdp::test {

struct CommandResult {
  int status;
  std::string output;  // stdout and stderr together
};

// The gvdp binary under test: $GVDP_BIN when set (binaries carried to another machine), else the
// one built beside the tests.
inline std::string gvdpBinary() {
  const char* env = std::getenv("GVDP_BIN");
  return env ? env : GVDP_BINARY;
}

inline CommandResult runGvdp(const std::string& args) {
  std::string cmd = gvdpBinary() + " " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

inline std::string tempDir(const std::string& name) {
  return ::testing::TempDir() + "gvdp_" + name + "_" + std::to_string(::getpid());
}

}  // namespace gvdp::test

#define GVDP_REQUIRE_GPU()                                                           \
  do {                                                                               \
    if (!::gvdp::cudaDeviceAvailable()) GTEST_SKIP() << ::gvdp::cudaDeviceSummary(); \
  } while (0)
