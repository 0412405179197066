// The watchdog over the host's waits on the GPU (base/watchdog.h), in child processes (death
// tests): its limit is process-wide, and this process's GPU tests must not run under it.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <thread>

#include "gvdp/base/error.h"
#include "gvdp/base/watchdog.h"

namespace gvdp::detail {
namespace {

using namespace std::chrono_literals;

TEST(WatchdogDeathTest, AWaitPastTheLimitEndsTheProcessNamingItsPhases) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        startWatchdog(0.2);
        WatchPhase frame("dp frame");
        WatchPhase sweep("dp sweep");
        WatchedWait wait("a copy to the host");
        std::this_thread::sleep_for(20s);
        std::exit(0);
      },
      testing::ExitedWithCode(3),
      "the GPU did not finish in 0.2 s: a copy to the host, in dp frame > dp sweep\n");
}

// Waits shorter than the limit, a phase left before the wait and idle time past the limit: the
// process goes on.
TEST(WatchdogDeathTest, ShortWaitsAndIdleTimeEndNothing) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        startWatchdog(0.3);
        for (int i = 0; i < 5; ++i) {
          { WatchPhase done("a phase that ended"); }
          WatchedWait wait("a short copy");
          std::this_thread::sleep_for(50ms);
        }
        std::this_thread::sleep_for(1s);
        std::exit(7);
      },
      testing::ExitedWithCode(7), "");
}

TEST(WatchdogDeathTest, ABadLimitIsAnInputErrorNamingIt) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        setenv("GVDP_WATCHDOG_S", "soon", 1);
        try {
          WatchedWait wait("anything");
        } catch (const InputError& e) {
          std::fputs(e.what(), stderr);
          std::exit(2);
        }
        std::exit(0);
      },
      testing::ExitedWithCode(2), "bad GVDP_WATCHDOG_S 'soon'");
}

}  // namespace
}  // namespace gvdp::detail
