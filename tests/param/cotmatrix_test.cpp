// cotmatrix: one invariant per test, on meshes made here (no shared data needed).
// Sign convention: ours is the positive semi-definite stiffness matrix (diagonal ≥ 0, xᵀLx ≥ 0),
// the negative of libigl's igl::cotmatrix under the same name.

#include "core/param/cotmatrix.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "tests/test_data.hpp"

namespace meshmark {
namespace {

TEST(Cotmatrix, IsSymmetric) {
  const Mesh m = test::icosphere(2);
  const Eigen::MatrixXd L = Eigen::MatrixXd(cotmatrix(m.V, m.F));
  EXPECT_LT((L - L.transpose()).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Cotmatrix, ConstantsAreInItsNullSpace) {
  const Mesh m = test::torus(12, 16);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(m.V.rows());
  EXPECT_LT((cotmatrix(m.V, m.F) * ones).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(Cotmatrix, IsPositiveSemidefiniteWithAPositiveDiagonalTheOppositeOfLibiglsSign) {
  const Mesh m = test::icosphere(2);
  const Eigen::MatrixXd L = Eigen::MatrixXd(cotmatrix(m.V, m.F));
  EXPECT_GT(L.diagonal().minCoeff(), 0.0);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(L);
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-10);
  // A linear function's Dirichlet energy is positive: xᵀLx > 0 for x = the height.
  const Eigen::VectorXd z = m.V.col(2);
  EXPECT_GT(z.dot(L * z), 0.0);
}

TEST(Cotmatrix, OnARightTriangleTheWeightsAreHalfTheCotangents) {
  // Right angle at vertex 0: cot 90° = 0 for edge (1,2); cot 45° = 1 for edges (0,1) and (0,2).
  Vertices V(3, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  Faces F(1, 3);
  F << 0, 1, 2;
  const Eigen::MatrixXd L = Eigen::MatrixXd(cotmatrix(V, F));
  EXPECT_NEAR(L(0, 1), -0.5, 1e-12);
  EXPECT_NEAR(L(0, 2), -0.5, 1e-12);
  EXPECT_NEAR(L(1, 2), 0.0, 1e-12);
  EXPECT_NEAR(L(0, 0), 1.0, 1e-12);
}

TEST(Cotmatrix, ClampsNegativeWeightsToTheMinimum) {
  // An obtuse triangle pair: the edge opposite two obtuse angles has a negative weight.
  Vertices V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0.5, 0.1, 0, 0.5, -0.1, 0;
  Faces F(2, 3);
  F << 0, 1, 2, 1, 0, 3;
  const Eigen::MatrixXd raw = Eigen::MatrixXd(cotmatrix(V, F, {.min_weight = -1e9}));
  ASSERT_GT(raw(0, 1), 0.0) << "the fixture should have a negative weight on edge (0,1)";
  const Eigen::MatrixXd clamped = Eigen::MatrixXd(cotmatrix(V, F, {.min_weight = 0.0}));
  EXPECT_LE(clamped(0, 1), 0.0);
}

}  // namespace
}  // namespace meshmark
