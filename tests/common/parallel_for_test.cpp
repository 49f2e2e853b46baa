// parallel_for: every index runs exactly once on any number of threads, and a worker that throws
// becomes an exception in the caller (the lowest index's, whatever the scheduling), never terminate.
#include <atomic>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/parallel_for.hpp"

namespace {

TEST(ParallelFor, EveryIndexRunsOnceOnAnyNumberOfThreads) {
  for (int threads : {0, 1, 2, 8}) {
    std::vector<std::atomic<int>> runs(1000);
    nano::parallel_for(runs.size(), threads, [&](std::size_t i) { ++runs[i]; });
    for (std::size_t i = 0; i < runs.size(); ++i) EXPECT_EQ(runs[i].load(), 1) << "index " << i << ", " << threads << " threads";
  }
  nano::parallel_for(0, 4, [](std::size_t) { FAIL() << "no task for an empty range"; });
}

TEST(ParallelFor, AThrowingWorkerBecomesTheCallersErrorAfterAllTasks) {
  for (int threads : {1, 2, 4}) {
    std::atomic<int> ran{0};
    try {
      nano::parallel_for(64, threads, [&](std::size_t i) {
        ++ran;
        if (i == 40 || i == 17) throw std::runtime_error("task " + std::to_string(i));
      });
      ADD_FAILURE() << "no exception with " << threads << " threads";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "task 17");  // the lowest index that threw
    }
    EXPECT_EQ(ran.load(), 64) << "every task runs even after one threw";
  }
  EXPECT_THROW(nano::parallel_for(8, 2, [](std::size_t i) { if (i == 5) throw std::bad_alloc(); }), std::bad_alloc);
}

}  // namespace
