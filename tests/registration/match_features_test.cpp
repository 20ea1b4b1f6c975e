// Local shape descriptors describe a surface whatever its pose, scale or winding, and a
// simplified, moved copy's descriptors vote for its pose.

#include "core/registration/match_features.hpp"

#include <gtest/gtest.h>

#include "core/attacks/similarity_transform.hpp"
#include "core/attacks/simplify.hpp"
#include "core/mesh/vertex_normals.hpp"
#include "core/metrics/compare_meshes.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

const Mesh& described_shape() { return test::procedural_mesh("creature_large"); }

TEST(DescribePoints, TheSameWhateverThePoseScaleOrTheNormalsSigns) {
  const ShapeFeatures features(described_shape(), 2000, 40, 2);
  std::vector<int> faces;
  const Vertices points = sample_surface(described_shape(), 2000, &faces);
  const Vertices face_normal = face_normals(described_shape().V, described_shape().F);
  Vertices normals(points.rows(), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) normals.row(i) = face_normal.row(faces[static_cast<std::size_t>(i)]);
  const Eigen::MatrixXd descriptors = describe_points(points, normals, 40, 2);
  EXPECT_EQ(descriptors, features.descriptors);
  for (Eigen::Index i = 0; i < descriptors.rows(); i += 97) EXPECT_NEAR(descriptors.row(i).sum(), 3, 1e-12);

  Similarity T;
  T.R = Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix();
  T.scale = 3.5;
  T.t = Eigen::Vector3d(-4, 1, 7);
  const Eigen::MatrixXd moved = describe_points(T.apply_to_rows(points), normals * T.R.transpose(), 40, 2);
  EXPECT_LT((moved - descriptors).cwiseAbs().mean(), 1e-4);  // rounding may cross a bin's edge

  Vertices flipped = normals;  // a surface wound inconsistently: every third normal turned over
  for (Eigen::Index i = 0; i < flipped.rows(); i += 3) flipped.row(i) *= -1;
  EXPECT_LT((describe_points(points, flipped, 40, 2) - descriptors).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(MatchFeatures, ASimplifiedMovedCopyVotesForItsPose) {
  const Mesh& original = described_shape();
  const ShapeFeatures features(original, 4000, 40, 2);
  const Similarity T = random_similarity(original, 4);
  const Mesh copy = transform_mesh(simplify(original, 0.25), T);
  const std::vector<Similarity> poses = match_features(copy, 1 / T.scale, features);
  ASSERT_FALSE(poses.empty());
  const double diagonal = (original.V.colwise().maxCoeff() - original.V.colwise().minCoeff()).norm();
  const double off =
      (poses.front().apply_to_rows(T.apply_to_rows(original.V)) - original.V).rowwise().norm().maxCoeff();
  EXPECT_LT(off / diagonal, 0.02);  // a start: ICP takes it the rest of the way
}

}  // namespace
}  // namespace meshmark
