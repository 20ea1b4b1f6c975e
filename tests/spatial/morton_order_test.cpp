#include "core/spatial/morton_order.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <set>

namespace meshmark {
namespace {

// A 4×4×4 lattice, shuffled: Z-order visits each 2×2×2 block whole before the next, and each
// block's corner cells in the order x, then y, then z.
TEST(MortonOrder, VisitsALatticeBlockByBlock) {
  std::vector<Eigen::RowVector3d> cells;
  for (int z = 0; z < 4; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) cells.emplace_back(x, y, z);
  std::vector<int> shuffled(cells.size());
  std::iota(shuffled.begin(), shuffled.end(), 0);
  std::reverse(shuffled.begin(), shuffled.end());
  Vertices points(static_cast<Eigen::Index>(cells.size()), 3);
  for (std::size_t i = 0; i < cells.size(); ++i) points.row(static_cast<Eigen::Index>(i)) = cells[shuffled[i]];
  const std::vector<std::int64_t> order = morton_order(points);
  ASSERT_EQ(order.size(), cells.size());
  EXPECT_EQ(std::set<std::int64_t>(order.begin(), order.end()).size(), cells.size());  // a permutation
  for (std::size_t block = 0; block < 8; ++block) {
    const Eigen::RowVector3d corner = points.row(order[8 * block]);
    for (std::size_t k = 0; k < 8; ++k) {
      const Eigen::RowVector3d p = points.row(order[8 * block + k]);
      // Within the block whose lowest corner comes first, and at the k-th corner (x is bit 0).
      EXPECT_EQ(p, corner + Eigen::RowVector3d(k & 1, (k >> 1) & 1, (k >> 2) & 1)) << block << " " << k;
    }
    EXPECT_EQ(std::fmod(corner.x(), 2.0), 0.0);
  }
}

TEST(MortonOrder, CoincidentAndNonFinitePointsStillGiveAPermutation) {
  Vertices points(5, 3);
  points << 1, 1, 1, 1, 1, 1, std::numeric_limits<double>::quiet_NaN(), 0, 0, 1, 1, 1, 1, 1, 1;
  const std::vector<std::int64_t> order = morton_order(points);
  EXPECT_EQ(std::set<std::int64_t>(order.begin(), order.end()), (std::set<std::int64_t>{0, 1, 2, 3, 4}));
  EXPECT_TRUE(morton_order(Vertices(0, 3)).empty());
}

}  // namespace
}  // namespace meshmark
