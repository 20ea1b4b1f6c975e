#include "core/util/bucket_sort.hpp"

#include <gtest/gtest.h>

#include <random>
#include <utility>

namespace meshmark {
namespace {

// Records ordered by a small key first, then by a second field: the bucketed order is std::sort's.
TEST(BucketSort, OrdersAsAComparisonSortDoes) {
  std::mt19937 random(3);
  for (const std::size_t keys : {1u, 7u, 1000u}) {
    std::vector<std::pair<std::size_t, int>> items(5000);
    for (auto& [key, value] : items)
      key = random() % keys, value = static_cast<int>(random() % 100);  // many equal records too
    auto expected = items;
    std::sort(expected.begin(), expected.end());
    bucket_sort(
        items, keys, [](const auto& item) { return item.first; }, std::less<>());
    EXPECT_EQ(items, expected) << keys << " keys";
  }
}

TEST(BucketSort, NothingToSortAndKeysFarBeyondTheRecordsAreLeftToTheComparisonSort) {
  std::vector<int> none;
  bucket_sort(
      none, 0, [](int v) { return static_cast<std::size_t>(v); }, std::less<>());
  EXPECT_TRUE(none.empty());
  EXPECT_TRUE(bucket_sort_pays(3000, 10000));
  EXPECT_FALSE(bucket_sort_pays(3, std::size_t{1} << 30));
}

}  // namespace
}  // namespace meshmark
