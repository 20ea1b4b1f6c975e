#include "core/registration/starting_poses.hpp"

#include <gtest/gtest.h>

#include "core/attacks/similarity_transform.hpp"
#include "core/mesh/example_shapes.hpp"
#include "core/metrics/compare_meshes.hpp"

namespace meshmark::registration {
namespace {

double turn_degrees(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a * b.transpose()).angle() * 180 / M_PI;
}

// A moved copy's principal axes are the original's turned: one of the 24 axis matchings is its
// pose, up to the sampling's noise, at its scale.
TEST(StartingPoses, OneAxisMatchingIsAMovedCopysPose) {
  const Mesh original = creature(3);
  const RegistrationTarget target(original);
  for (const std::uint64_t seed : {1, 2, 3}) {
    const Similarity T = random_similarity(original, seed);
    const Similarity back = T.inverse();
    const Mesh moved = transform_mesh(original, T);
    const NamedStarts starts = starting_poses(principal_moments(sample_surface(moved, 20000)), target, false);
    double best = 180;
    for (const auto& [pose, name] : starts)
      if (std::abs(pose.scale / back.scale - 1) < 0.01) best = std::min(best, turn_degrees(pose.R, back.R));
    EXPECT_LT(best, 2.0) << "seed " << seed;
  }
}

// Turns only where the axes cannot tell them apart: none for distinct variances, 23 about the
// odd axis of a bottle, 96 for a ball.
TEST(StartingPoses, AmbiguousTurnsOnlyWhereVariancesAreAlike) {
  const Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  EXPECT_TRUE(ambiguous_turns(Eigen::Vector3d(9, 4, 1), axes).empty());
  const auto bottle = ambiguous_turns(Eigen::Vector3d(9, 1, 1), axes);
  ASSERT_EQ(bottle.size(), 23u);
  for (const Eigen::Matrix3d& turn : bottle)
    EXPECT_LT((turn * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitX()).norm(), 1e-12);
  EXPECT_EQ(ambiguous_turns(Eigen::Vector3d(1, 1, 1), axes).size(), 96u);
}

// A search again turns by 30° about every axis and by 15° about the one nearest to a symmetry
// (its companions' variances the most alike: here the first, 4 against 3.5), each turn about
// its own axis.
TEST(StartingPoses, TurnsAboutTheAxisNearestASymmetryComeEvery15Degrees) {
  const Eigen::Matrix3d axes = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const std::vector<Eigen::Matrix3d> turns = turns_about_axes(Eigen::Vector3d(9, 4, 3.5), axes);
  ASSERT_EQ(turns.size(), 11u + 5u + 5u);
  for (std::size_t k = 0; k < turns.size(); ++k) {
    const int axis = k < 11 ? 0 : k < 16 ? 1 : 2;
    const double step = axis == 0 ? 15 : 30, index = axis == 0 ? k + 1 : (k - (axis == 1 ? 11 : 16)) + 1;
    EXPECT_LT((turns[k] * axes.col(axis) - axes.col(axis)).norm(), 1e-12) << k;
    EXPECT_NEAR(Eigen::AngleAxisd(turns[k]).angle() * 180 / M_PI, step * index, 1e-9) << k;
  }
}

// The vertex spacing scales with the copy and is kept by a cut: the spacing starts' scale is the
// copy's exactly.
TEST(StartingPoses, TheSpacingScaleIsACopysScale) {
  const Mesh original = creature(3);
  const RegistrationTarget target(original);
  Similarity T;
  T.scale = 2.5;
  EXPECT_NEAR(vertex_spacing(transform_mesh(original, T)), 2.5 * vertex_spacing(original), 1e-12);
  EXPECT_NEAR(spacing_scale(transform_mesh(original, T), target), 1 / 2.5, 1e-12);
  EXPECT_EQ(vertex_spacing(Mesh{}), 0.0);
}

}  // namespace
}  // namespace meshmark::registration
