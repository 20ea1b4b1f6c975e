#include "core/util/parallel_for.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <thread>

#include <stdexcept>
#include <vector>

namespace meshmark {
namespace {

TEST(ParallelFor, VisitsEveryIndexExactlyOnce) {
  for (const int threads : {0, 1, 3, 8})
    for (const std::int64_t n : {0, 1, 7, 2048, 100001}) {
      std::vector<int> visits(static_cast<std::size_t>(n), 0);
      parallel_for(
          n, threads,
          [&](std::int64_t begin, std::int64_t end) {
            for (std::int64_t i = begin; i < end; ++i) ++visits[i];
          },
          16);
      for (std::int64_t i = 0; i < n; ++i) ASSERT_EQ(visits[i], 1) << threads << " threads, n " << n << " index " << i;
    }
}

TEST(ParallelFor, RunsOnExactlyTheThreadsItIsGiven) {
  for (const int threads : {1, 2, 5}) {
    std::mutex mutex;
    std::set<std::thread::id> seen;
    parallel_for(
        100000, threads,
        [&](std::int64_t, std::int64_t) {
          std::lock_guard lock(mutex);
          seen.insert(std::this_thread::get_id());
        },
        16);
    EXPECT_EQ(seen.size(), static_cast<std::size_t>(threads));
    EXPECT_TRUE(seen.count(std::this_thread::get_id())) << "the caller takes a block itself";
  }
}

TEST(ParallelFor, ZeroThreadsMeansTheHardwaresAtMostEight) {
  EXPECT_EQ(resolve_threads(0), hardware_threads());
  EXPECT_EQ(resolve_threads(3), 3);
  EXPECT_GE(hardware_threads(), 1);
  EXPECT_LE(hardware_threads(), 8);
}

TEST(ParallelFor, AnExceptionInAnyBlockReachesTheCaller) {
  EXPECT_THROW(parallel_for(
                   100000, 4,
                   [](std::int64_t begin, std::int64_t end) {
                     if (end == 100000 && begin > 0) throw std::runtime_error("last block");
                     if (begin == 0 && end == 100000) throw std::runtime_error("single block");
                   },
                   16),
               std::runtime_error);
}

TEST(ParallelForEach, VisitsEveryIndexExactlyOnceOnAnyThreadCount) {
  for (const int threads : {1, 3, 8}) {
    std::vector<std::atomic<int>> visits(1000);
    parallel_for_each(1000, threads, [&](std::int64_t i) { ++visits[static_cast<std::size_t>(i)]; });
    for (std::size_t i = 0; i < visits.size(); ++i)
      ASSERT_EQ(visits[i].load(), 1) << threads << " threads, index " << i;
  }
}

TEST(ParallelForEach, AnExceptionStopsNewWorkAndReachesTheCaller) {
  // On one thread, nothing after the failing index starts.
  std::atomic<int> started{0};
  const auto body = [&](std::int64_t i) {
    ++started;
    if (i == 10) throw std::runtime_error("trial 10");
    std::this_thread::sleep_for(std::chrono::microseconds(50));  // so that the others cannot finish first
  };
  EXPECT_THROW(parallel_for_each(100000, 1, body), std::runtime_error);
  EXPECT_EQ(started.load(), 11);
  // On four, the others stop soon after (all 100,000 would take them over a second).
  started = 0;
  EXPECT_THROW(parallel_for_each(100000, 4, body), std::runtime_error);
  EXPECT_LT(started.load(), 50000);
}

}  // namespace
}  // namespace meshmark
