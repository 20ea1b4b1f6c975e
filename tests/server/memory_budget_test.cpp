#include "server/memory_budget.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace meshmark::server {
namespace {

TEST(MemoryBudget, ReservationsFitTogetherUnderTheCeilingAndAreGivenBackWhenDropped) {
  MemoryBudget budget(100);
  auto a = budget.try_reserve(60);
  ASSERT_TRUE(a);
  EXPECT_FALSE(budget.try_reserve(41)) << "60 + 41 is over the ceiling";
  {
    auto b = budget.try_reserve(40);
    ASSERT_TRUE(b);
    EXPECT_EQ(budget.reserved(), 100u);
  }
  EXPECT_EQ(budget.reserved(), 60u);
  MemoryReservation moved = std::move(*a);
  a.reset();
  EXPECT_EQ(budget.reserved(), 60u) << "a moved reservation is held once";
  moved = MemoryReservation();
  EXPECT_EQ(budget.reserved(), 0u);
  EXPECT_FALSE(budget.try_reserve(101)) << "more than the ceiling never fits at once";
}

TEST(MemoryBudget, AWaitingReservationTakesItsPlaceWhenAnotherIsDropped) {
  MemoryBudget budget(100);
  auto held = budget.try_reserve(80);
  std::size_t got = 0;
  std::thread waiter([&] { got = budget.reserve(50, JobControl{}).bytes(); });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(got, 0u) << "50 does not fit beside 80";
  held.reset();
  waiter.join();
  EXPECT_EQ(got, 50u);
}

TEST(MemoryBudget, MoreThanTheCeilingWaitsForAllOfItAndThenRunsAlone) {
  MemoryBudget budget(100);
  const MemoryReservation whole = budget.reserve(1'000, JobControl{});
  EXPECT_EQ(whole.bytes(), 100u);
  EXPECT_FALSE(budget.try_reserve(1));
}

TEST(MemoryBudget, AWaitEndsWithTheCancelOrTheDeadline) {
  MemoryBudget budget(100);
  auto held = budget.try_reserve(100);
  std::atomic<bool> cancel{true};
  JobControl canceled;
  canceled.cancel = &cancel;
  EXPECT_THROW(budget.reserve(1, canceled), Canceled);
  JobControl late;
  late.deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(100);
  EXPECT_THROW(budget.reserve(1, late), TimeLimitExceeded);
  EXPECT_EQ(budget.reserved(), 100u);
}

TEST(MemoryBudget, TheMachinesMemoryIsKnown) { EXPECT_GT(available_memory_bytes(), std::size_t{64} << 20); }

}  // namespace
}  // namespace meshmark::server
