#include "core/param/exact_orientation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace meshmark {
namespace {

TEST(ExactOrientation, CounterClockwiseSeenFromOutsideIsPositive) {
  EXPECT_EQ(orientation_sign({1, 0, 0}, {0, 1, 0}, {0, 0, 1}), 1);
  EXPECT_EQ(orientation_sign({1, 0, 0}, {0, 0, 1}, {0, 1, 0}), -1);
}

TEST(ExactOrientation, ExactlyCoplanarWithTheOriginIsZero) {
  const Eigen::Vector3d a(0.125, 0.25, 0.375), b(0.75, -0.3125, 0.0625);  // dyadic: a + b is exact
  EXPECT_EQ(orientation_sign(a, b, a + b), 0);
  EXPECT_EQ(orientation_sign(a, b, 2 * a), 0);
}

TEST(ExactOrientation, OneUlpOffThePlaneIsDecidedCorrectly) {
  // c = a + b lies in the plane of a and b; nudging one coordinate by an ulp moves it off by a
  // tiny amount whose side the fast filter cannot see.
  const Eigen::Vector3d a(0.125, 0.25, 0.375), b(0.75, -0.3125, 0.0625);  // dyadic: a + b is exact
  const Eigen::Vector3d n = a.cross(b);
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d up = a + b, down = a + b;
    up[k] = std::nextafter(up[k], n[k] > 0 ? 10.0 : -10.0);
    down[k] = std::nextafter(down[k], n[k] > 0 ? -10.0 : 10.0);
    EXPECT_EQ(orientation_sign(a, b, up), 1) << k;
    EXPECT_EQ(orientation_sign(a, b, down), -1) << k;
  }
}

TEST(ExactOrientation, SwappingTwoPointsFlipsTheSign) {
  const Eigen::Vector3d a(1e-9, 1, 3e-8), b(2e-9, 1, 1e-8), c(3e-9, 1, -1e-8);
  EXPECT_EQ(orientation_sign(a, b, c), -orientation_sign(b, a, c));
}

}  // namespace
}  // namespace meshmark
