#include "core/util/parallel_for.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace meshmark {
namespace {

TEST(ParallelFor, VisitsEveryIndexExactlyOnce) {
  for (const std::int64_t n : {0, 1, 7, 2048, 100001}) {
    std::vector<int> visits(static_cast<std::size_t>(n), 0);
    parallel_for(n, [&](std::int64_t begin, std::int64_t end) {
      for (std::int64_t i = begin; i < end; ++i) ++visits[i];
    }, 16);
    for (std::int64_t i = 0; i < n; ++i) ASSERT_EQ(visits[i], 1) << "n " << n << " index " << i;
  }
}

TEST(ParallelFor, AnExceptionInAnyBlockReachesTheCaller) {
  EXPECT_THROW(parallel_for(100000, [](std::int64_t begin, std::int64_t end) {
    if (end == 100000 && begin > 0) throw std::runtime_error("last block");
    if (begin == 0 && end == 100000) throw std::runtime_error("single block");
  }, 16), std::runtime_error);
}

}  // namespace
}  // namespace meshmark
