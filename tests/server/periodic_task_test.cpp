#include "server/periodic_task.hpp"

#include <gtest/gtest.h>

#include <atomic>

namespace meshmark::server {
namespace {

TEST(PeriodicTask, RunsEveryIntervalUntilDestroyedAndNoMoreAfter) {
  std::atomic<int> runs{0};
  {
    const PeriodicTask task(std::chrono::milliseconds(5), [&runs] { ++runs; });
    while (runs < 3) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  const int at_stop = runs;
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  EXPECT_EQ(runs, at_stop);
}

TEST(PeriodicTask, StopsAtOnceWithoutWaitingOutItsInterval) {
  const auto start = std::chrono::steady_clock::now();
  {
    const PeriodicTask task(std::chrono::hours(1), [] { ADD_FAILURE() << "ran before its interval"; });
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

}  // namespace
}  // namespace meshmark::server
