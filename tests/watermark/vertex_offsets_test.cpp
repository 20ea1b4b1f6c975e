// Reading a copy vertex by vertex: its offsets are found whatever the order and pose, exactly
// where the copy keeps the original's vertices, and not at all where it does not.

#include "core/watermark/vertex_offsets.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <numeric>
#include <random>

#include "tests/test_data.hpp"

namespace meshmark {
namespace {

// The mesh with its vertices in a shuffled order and its faces renumbered to match.
Mesh shuffled(const Mesh& mesh) {
  std::vector<int> order(static_cast<std::size_t>(mesh.V.rows()));
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(5));
  std::vector<int> place(order.size());
  Mesh out{Vertices(mesh.V.rows(), 3), mesh.F};
  for (std::size_t i = 0; i < order.size(); ++i) {
    out.V.row(static_cast<Eigen::Index>(i)) = mesh.V.row(order[i]);
    place[static_cast<std::size_t>(order[i])] = static_cast<int>(i);
  }
  for (Eigen::Index f = 0; f < out.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) out.F(f, k) = place[static_cast<std::size_t>(mesh.F(f, k))];
  return out;
}

// The mesh stored face by face: three vertices of its own for every face.
Mesh split_by_face(const Mesh& mesh) {
  Mesh out{Vertices(3 * mesh.F.rows(), 3), Faces(mesh.F.rows(), 3)};
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      out.V.row(3 * f + k) = mesh.V.row(mesh.F(f, k));
      out.F(f, k) = static_cast<int>(3 * f + k);
    }
  return out;
}

// Each vertex pushed by `size` along a direction of its own.
Vertices scattered_field(Eigen::Index rows, double size) {
  Vertices field(rows, 3);
  for (Eigen::Index i = 0; i < rows; ++i)
    field.row(i) = size * Eigen::RowVector3d(std::sin(7.0 * i), std::cos(3.0 * i), std::sin(11.0 * i + 1)).normalized();
  return field;
}

Vertices turned(const Vertices& V, double angle, double scale, const Eigen::RowVector3d& move) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  return (scale * V * R.transpose()).rowwise() + move;
}

// The largest entry of a − b once the small similarities at the original's vertices are removed.
double similarity_free_difference(const Vertices& original, const Vertices& a, const Vertices& b) {
  const Eigen::MatrixXd fields =
      similarity_fields(original, std::vector<char>(static_cast<std::size_t>(original.rows()), 1));
  const Eigen::MatrixXd difference = a - b;
  const Eigen::VectorXd flat = Eigen::Map<const Eigen::VectorXd>(difference.data(), difference.size());
  return (flat - fields * (fields.transpose() * flat)).cwiseAbs().maxCoeff();
}

TEST(VertexOffsets, AReorderedMovedCopyGivesBackItsOffsetsAtEveryVertex) {
  const Mesh original = test::icosphere(3);
  const Vertices field = scattered_field(original.V.rows(), 1e-3);
  // Registration gives the copy back in place; the offsets are read on the copy as it came.
  const Mesh aligned = shuffled({original.V + field, original.F});
  const Vertices copy = turned(aligned.V, 0.7, 1.5, {4, -2, 1});
  const auto offsets = corresponding_offsets(original, aligned, copy, median_edge_length(original));
  ASSERT_TRUE(offsets.has_value());
  EXPECT_EQ(std::count(offsets->corresponded.begin(), offsets->corresponded.end(), 1), original.V.rows());
  // Up to the similarity fitted between the pairs, the offsets are the field.
  EXPECT_LT(similarity_free_difference(original.V, offsets->offset, field), 1e-6);
}

// A copy in its vertex order pairs by it even where each vertex moved further than half an edge
// (a mark on a dense mesh), which leaves mutual nearest neighbours without partners.
TEST(VertexOffsets, ACopyInOrderPairsByItWhereTheMarkMovedVerticesFurtherThanHalfAnEdge) {
  const Mesh original = test::icosphere(3);
  const double edge = median_edge_length(original);
  const Vertices field = scattered_field(original.V.rows(), 0.8 * edge);
  const Vertices aligned = original.V + field;
  const Vertices copy = turned(aligned, 0.7, 1.5, {4, -2, 1});
  EXPECT_FALSE(corresponding_offsets(original, Mesh{aligned, Faces()}, copy, edge).has_value());
  const auto offsets = offsets_in_order(original.V, aligned, copy, 2 * edge);
  ASSERT_TRUE(offsets.has_value());
  EXPECT_EQ(std::count(offsets->corresponded.begin(), offsets->corresponded.end(), 1), original.V.rows());
  // Up to the similarity fitted between the pairs, the field: within 5 % of an edge (the field is
  // 80 %; the fit is a similarity of the original plus the field, linear only to first order).
  EXPECT_LT(similarity_free_difference(original.V, offsets->offset, field), 0.05 * edge);
  // Vertices beyond the tolerance are not paired; too few paired, nothing is read.
  EXPECT_FALSE(offsets_in_order(original.V, aligned, copy, 0.5 * edge).has_value());
}

// Reordered, a copy where one vertex in twenty moved 0.8 of an edge pairs through the faces it
// shares with the original: every vertex, none with a neighbour's partner (mutual nearest alone
// leaves those unpaired, or pairs them with a neighbour's partner).
TEST(VertexOffsets, AReorderedCopyPairsThroughItsFacesWhereTheMarkMovedVerticesFurtherThanHalfAnEdge) {
  const Mesh original = test::icosphere(3);
  const double edge = median_edge_length(original);
  Vertices field = scattered_field(original.V.rows(), 0.05 * edge);
  for (Eigen::Index i = 0; i < field.rows(); i += 20) field.row(i) *= 16;
  const Mesh aligned = shuffled({original.V + field, original.F});
  const auto offsets = corresponding_offsets(original, aligned, aligned.V, edge);
  ASSERT_TRUE(offsets.has_value());
  EXPECT_EQ(std::count(offsets->corresponded.begin(), offsets->corresponded.end(), 1), original.V.rows());
  EXPECT_LT(similarity_free_difference(original.V, offsets->offset, field), 0.05 * edge);
}

// A copy stored face by face shares no face with the original: its mutual nearest pairs stand.
TEST(VertexOffsets, ACopyStoredFaceByFaceKeepsItsMutualNearestPairs) {
  const Mesh original = test::icosphere(3);
  const Vertices field = scattered_field(original.V.rows(), 1e-3);
  const Mesh aligned = split_by_face({original.V + field, original.F});
  const auto offsets = corresponding_offsets(original, aligned, aligned.V, median_edge_length(original));
  ASSERT_TRUE(offsets.has_value());
  EXPECT_EQ(std::count(offsets->corresponded.begin(), offsets->corresponded.end(), 1), original.V.rows());
  EXPECT_LT(similarity_free_difference(original.V, offsets->offset, field), 1e-6);
}

TEST(VertexOffsets, ACopyOnOtherVerticesHasNoCorrespondence) {
  const Mesh original = test::icosphere(3);
  const Vertices elsewhere = turned(original.V, 0.3, 1.0, {0, 0, 0});  // the same sphere, its vertices moved on it
  EXPECT_FALSE(
      corresponding_offsets(original, {elsewhere, original.F}, elsewhere, median_edge_length(original)).has_value());
}

TEST(VertexOffsets, TheSimilarityFieldsAreOrthonormalAndHoldASmallSimilarity) {
  const Mesh original = test::icosphere(2);
  const std::vector<char> all(static_cast<std::size_t>(original.V.rows()), 1);
  const Eigen::MatrixXd fields = similarity_fields(original.V, all);
  EXPECT_LT((fields.transpose() * fields - Eigen::MatrixXd::Identity(7, 7)).cwiseAbs().maxCoeff(), 1e-12);
  // A tiny turn, scale and move of the original lies in their span.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1e-6, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Vertices moved = ((1 + 1e-6) * original.V * R.transpose()).rowwise() + Eigen::RowVector3d(1e-6, 0, -2e-6);
  const Eigen::MatrixXd change = moved - original.V;
  const Eigen::VectorXd flat = Eigen::Map<const Eigen::VectorXd>(change.data(), change.size());
  EXPECT_LT((flat - fields * (fields.transpose() * flat)).norm(), 1e-6 * flat.norm());
}

}  // namespace
}  // namespace meshmark
