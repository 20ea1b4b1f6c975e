// The nearest-point query against brute force, with and without a hint, ties included.

#include "core/spatial/point_index.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <random>

namespace meshmark {
namespace {

// The least (squared distance, index) over all points: what the index promises.
std::pair<int, double> brute_force(const Vertices& points, const Eigen::Vector3d& p) {
  std::pair<int, double> best{-1, std::numeric_limits<double>::infinity()};
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const double d2 = (points.row(i).transpose() - p).squaredNorm();
    if (d2 < best.second) best = {static_cast<int>(i), d2};
  }
  return best;
}

// Random points, a few of them repeated (exact ties), queried near them and far away.
TEST(PointIndex, TheNearestPointIsTheSameWithAnyHintAndTiesGoToTheLowerIndex) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  Vertices points(3000, 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) points.row(i) << unit(rng), unit(rng), unit(rng);
  for (Eigen::Index i = 0; i < 300; ++i) points.row(2000 + i) = points.row(6 * i);  // repeated later
  const PointIndex index(points);
  std::uniform_int_distribution<int> any(0, static_cast<int>(points.rows()) - 1);
  for (int q = 0; q < 4000; ++q) {
    const Eigen::Vector3d p = q % 2 ? Eigen::Vector3d(points.row(any(rng)).transpose())  // on a point
                                    : Eigen::Vector3d(3 * unit(rng), 3 * unit(rng), 3 * unit(rng));
    const auto expected = brute_force(points, p);
    const auto plain = index.nearest(p);
    ASSERT_EQ(plain.first, expected.first) << "query " << q;
    ASSERT_EQ(plain.second, expected.second) << "query " << q;
    for (const int hint : {any(rng), expected.first, -1, static_cast<int>(points.rows()) + 3}) {
      const auto hinted = index.nearest(p, hint);
      ASSERT_EQ(hinted.first, expected.first) << "query " << q << ", hint " << hint;
      ASSERT_EQ(hinted.second, expected.second) << "query " << q << ", hint " << hint;
    }
  }
}

TEST(PointIndex, AnEmptySetHasNoNearestPoint) {
  const Vertices none(0, 3);
  const PointIndex index(none);
  EXPECT_EQ(index.nearest(Eigen::Vector3d::Zero()).first, -1);
  EXPECT_EQ(index.nearest(Eigen::Vector3d::Zero(), 0).first, -1);
}

}  // namespace
}  // namespace meshmark
