// The watchdog (base/watchdog.h) over a real wait on the GPU, in a child process (a death test):
// a copy into pageable memory waits for its stream inside cudaMemcpyAsync, so readDevice's watch
// must start before that call. Started after it, the watch missed dp's hang (BENCHMARKS.md,
// session 35). Compiled only in a CUDA build; runs only with a device.
#include <gtest/gtest.h>

#include <cstdlib>

#include "gvdp/base/cuda_util.h"
#include "test_util.h"

namespace gvdp::detail {
namespace {

__global__ void holdTheStream(uint64_t ns, uint32_t* done) {
  uint64_t start = 0, now = 0;
  asm volatile("mov.u64 %0, %%globaltimer;" : "=l"(start));
  do {
    __nanosleep(1000000);
    asm volatile("mov.u64 %0, %%globaltimer;" : "=l"(now));
  } while (now - start < ns);
  *done = 1u;
}

// Reads a word the stream computes only after 5 s, under a watchdog of 0.5 s.
void readAfterAHeldStream() {
  startWatchdog(0.5);
  DeviceBuffer<uint32_t> done(1);
  cudaStream_t stream = nullptr;
  GVDP_CUDA_CHECK(cudaStreamCreate(&stream));
  holdTheStream<<<1, 1, 0, stream>>>(5'000'000'000ull, done.data());
  GVDP_CUDA_CHECK(cudaGetLastError());
  uint32_t host = 0;  // on the stack: pageable
  WatchPhase phase("a test");
  readDevice(&host, done.data(), sizeof host, stream);
  std::exit(0);  // the wait went unwatched
}

TEST(WatchdogGpuDeathTest, ACopyIntoPageableMemoryIsWatchedFromItsCall) {
  GVDP_REQUIRE_GPU();
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(readAfterAHeldStream(), testing::ExitedWithCode(3),
              "the GPU did not finish in 0.5 s: a copy to the host, in a test");
}

}  // namespace
}  // namespace gvdp::detail
