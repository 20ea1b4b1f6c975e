#include "core/mesh/surface_moments.hpp"

#include <gtest/gtest.h>

#include "tests/test_data.hpp"

namespace meshmark {
namespace {

// A unit cube's surface: centroid at its centre, variance 5/36 along every axis (along x, the two
// faces across it add 1/4 each and the four along it 1/12 each, over a total area of 6).
TEST(SurfaceMoments, AreExactOnACubesSurface) {
  Mesh cube = test::cube();
  cube.V.rowwise() += Eigen::RowVector3d(2, -1, 5);
  const SurfaceMoments m = surface_moments(cube);
  EXPECT_LT((m.centroid - Eigen::Vector3d(2.5, -0.5, 5.5)).norm(), 1e-12);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(m.variances[k], 5.0 / 36.0, 1e-12);
}

// A ball's variances are alike (its axes are noise); stretched by a third along y, y leads.
TEST(SurfaceMoments, TellABallFromAStretchedOne) {
  const Mesh ball = test::icosphere(3);
  const Eigen::Vector3d v = surface_moments(ball).variances;
  EXPECT_TRUE(variances_alike(v[0], v[1]) && variances_alike(v[1], v[2]));
  Mesh stretched = ball;
  stretched.V.col(1) *= 4.0 / 3.0;
  const SurfaceMoments m = surface_moments(stretched);
  EXPECT_FALSE(variances_alike(m.variances[0], m.variances[1]));
  EXPECT_NEAR(std::abs(m.axes(1, 0)), 1.0, 1e-9);
  EXPECT_TRUE(variances_alike(m.variances[1], m.variances[2]));  // x and z: a turn about y is ambiguous
}

}  // namespace
}  // namespace meshmark
