#include "rangefill/core/parallel.h"

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace rangefill {
namespace {

// Every task runs once whatever the number of threads, more threads than tasks included.
TEST(ParallelFor, RunsEveryTaskOnce) {
  for (const int threads : {1, 2, 5, 300}) {
    std::vector<std::atomic<int>> runs(100);
    parallel_for(100, threads, [&](int i) { ++runs[i]; });
    for (int i = 0; i < 100; ++i) EXPECT_EQ(runs[i], 1) << "task " << i << ", " << threads;
  }
  int none = 0;
  parallel_for(0, 4, [&](int) { ++none; });
  EXPECT_EQ(none, 0);
}

// Tasks 3 and 7 throw: the calling thread gets task 3's exception at any thread count (3 is
// handed out before 7 and runs to its end), every task before it ran, and on one thread none
// after it.
TEST(ParallelFor, RethrowsTheFirstFailureOnTheCallingThread) {
  for (const int threads : {1, 2, 4}) {
    std::vector<std::atomic<int>> runs(50);
    try {
      parallel_for(50, threads, [&](int i) {
        ++runs[i];
        if (i == 3 || i == 7) throw std::runtime_error("task " + std::to_string(i));
      });
      ADD_FAILURE() << "no exception with " << threads << " threads";
    } catch (const std::runtime_error& error) {
      EXPECT_STREQ(error.what(), "task 3") << threads;
    }
    for (int i = 0; i <= 3; ++i) EXPECT_EQ(runs[i], 1) << i;
    if (threads == 1) {
      EXPECT_EQ(runs[4], 0) << "a task ran after the failure";
    }
  }
}

}  // namespace
}  // namespace rangefill
