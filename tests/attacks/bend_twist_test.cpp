// Twist and bend on a long flat ribbon along x (width along y): the ends turn by the angle asked,
// lengths along the axis are kept, a zero angle changes nothing, and impossible angles are refused.

#include "core/attacks/bend_twist.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace meshmark {
namespace {

constexpr double kLength = 10, kWidth = 1;
constexpr int kAlong = 60, kAcross = 4;

Mesh ribbon() {
  Mesh m;
  m.V.resize((kAlong + 1) * (kAcross + 1), 3);
  for (int i = 0; i <= kAlong; ++i)
    for (int j = 0; j <= kAcross; ++j)
      m.V.row(i * (kAcross + 1) + j) << kLength * i / kAlong - kLength / 2, kWidth * j / kAcross - kWidth / 2, 0;
  m.F.resize(2 * kAlong * kAcross, 3);
  int f = 0;
  for (int i = 0; i < kAlong; ++i)
    for (int j = 0; j < kAcross; ++j) {
      const int a = i * (kAcross + 1) + j, b = a + kAcross + 1;
      m.F.row(f++) << a, b, a + 1;
      m.F.row(f++) << a + 1, b, b + 1;
    }
  return m;
}

// The vector across the ribbon at its end `i` (first or last row of vertices).
Eigen::Vector3d across(const Mesh& m, int i) {
  return m.V.row(i * (kAcross + 1) + kAcross) - m.V.row(i * (kAcross + 1));
}

Eigen::Vector3d centre(const Mesh& m, int i) { return m.V.row(i * (kAcross + 1) + kAcross / 2); }

TEST(Twist, TurnsOneEndAgainstTheOtherByTheAngleAndKeepsDistancesToTheAxis) {
  const Mesh twisted = twist(ribbon(), 30);
  const double cosine = across(twisted, 0).normalized().dot(across(twisted, kAlong).normalized());
  EXPECT_NEAR(std::acos(cosine) * 180 / M_PI, 30, 1e-6);
  for (Eigen::Index v = 0; v < twisted.V.rows(); ++v) {
    const Eigen::Vector3d before = ribbon().V.row(v), after = twisted.V.row(v);
    // The axis is the ribbon's centre line (x); the centroid is the origin.
    EXPECT_NEAR(std::hypot(after.y(), after.z()), std::abs(before.y()), 1e-12);
    EXPECT_NEAR(std::abs(after.x()), std::abs(before.x()), 1e-12);
  }
}

TEST(Bend, RollsTheAxisOntoAnArcOfTheAngleKeepingItsLength) {
  const double degrees = 40, radians = degrees * M_PI / 180;
  const Mesh bent = bend(ribbon(), degrees);
  const double cosine = across(bent, 0).normalized().dot(across(bent, kAlong).normalized());
  EXPECT_NEAR(std::acos(cosine) * 180 / M_PI, degrees, 1e-6);
  const double radius = kLength / radians;  // an arc of the ribbon's length
  EXPECT_NEAR((centre(bent, kAlong) - centre(bent, 0)).norm(), 2 * radius * std::sin(radians / 2), 1e-9);
  double centre_line = 0;
  for (int i = 0; i < kAlong; ++i) centre_line += (centre(bent, i + 1) - centre(bent, i)).norm();
  EXPECT_NEAR(centre_line, kLength, 1e-3 * kLength);  // a polyline on the arc: a little shorter
  EXPECT_LT(centre_line, kLength);
}

TEST(BendTwist, ZeroDegreesChangeNothingAndTooManyAreRefused) {
  EXPECT_TRUE(twist(ribbon(), 0).V.isApprox(ribbon().V, 1e-15));
  EXPECT_EQ(bend(ribbon(), 0).V, ribbon().V);
  EXPECT_THROW(twist(ribbon(), 400), std::invalid_argument);
  EXPECT_THROW(bend(ribbon(), -181), std::invalid_argument);
  EXPECT_THROW(bend(ribbon(), std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace meshmark
