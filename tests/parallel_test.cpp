#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

#include "gvdp/base/parallel.h"

namespace gvdp::detail {

// Every index runs exactly once, across back-to-back runs with different chunk sizes: a worker
// that wakes late for one run must not pair its chunk size with the next run's counter.
TEST(ThreadPool, EveryIndexRunsExactlyOnceAcrossBackToBackRuns) {
  ThreadPool pool(16);
  std::vector<std::atomic<int>> hits(5000);
  const int64_t CHUNKS[] = {64, 1, 7, 32, 3};
  for (int run = 0; run < 3000; ++run) {
    int64_t n = 1 + (run * 7919) % 5000;
    for (int64_t i = 0; i < n; ++i) hits[i] = 0;
    pool.run(n, CHUNKS[run % 5], [&](int64_t b, int64_t e, int) {
      for (int64_t i = b; i < e; ++i) hits[i].fetch_add(1, std::memory_order_relaxed);
    });
    for (int64_t i = 0; i < n; ++i) ASSERT_EQ(hits[i].load(), 1) << "run " << run << " index " << i;
  }
}

// Runs from several threads at once (two renderers on threads of their own, as `gvdp serve`
// and a user's program may have) take turns: every index of every run exactly once.
TEST(ThreadPool, RunsFromSeveralThreadsTakeTurns) {
  ThreadPool pool(4);
  constexpr int CALLERS = 4, RUNS = 200, N = 1000;
  std::vector<std::vector<std::atomic<int>>> hits(CALLERS);
  for (auto& h : hits) h = std::vector<std::atomic<int>>(N);
  std::vector<std::thread> callers;
  for (int c = 0; c < CALLERS; ++c)
    callers.emplace_back([&, c] {
      for (int r = 0; r < RUNS; ++r)
        pool.run(N, 1 + (r + c) % 9, [&](int64_t b, int64_t e, int) {
          for (int64_t i = b; i < e; ++i) hits[c][i].fetch_add(1);
        });
    });
  for (std::thread& t : callers) t.join();
  for (int c = 0; c < CALLERS; ++c)
    for (int i = 0; i < N; ++i)
      ASSERT_EQ(hits[c][i].load(), RUNS) << "caller " << c << " index " << i;
}

}  // namespace gvdp::detail
