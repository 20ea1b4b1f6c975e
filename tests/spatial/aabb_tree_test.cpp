// The closest-point query against brute force over every triangle, with and without a hint.

#include "core/spatial/aabb_tree.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "tests/procedural_meshes.hpp"

namespace meshmark {
namespace {

// The least (distance, face) over all triangles: what the tree promises, ties to the lower face.
TriangleHit brute_force(const Mesh& mesh, const Eigen::Vector3d& p) {
  TriangleHit best;
  best.distance_squared = std::numeric_limits<double>::infinity();
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    Eigen::Vector3d bary;
    const Eigen::Vector3d q = closest_point_on_triangle(p, mesh.V.row(mesh.F(f, 0)), mesh.V.row(mesh.F(f, 1)),
                                                        mesh.V.row(mesh.F(f, 2)), bary);
    if (const double d2 = (q - p).squaredNorm(); d2 < best.distance_squared)
      best = TriangleHit{static_cast<int>(f), 0, bary, q, d2};
  }
  return best;
}

TEST(AabbTree, TheClosestPointIsBruteForcesWhateverTheHint) {
  const Mesh& mesh = test::procedural_mesh("creature");
  const AabbTree tree(mesh.V, mesh.F);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  std::uniform_int_distribution<int> face(-1, static_cast<int>(mesh.F.rows()) - 1);
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    const TriangleHit exact = brute_force(mesh, p);
    const auto plain = tree.closest_point(p);
    ASSERT_TRUE(plain);
    EXPECT_EQ(plain->face, exact.face);
    EXPECT_DOUBLE_EQ(plain->distance_squared, exact.distance_squared);
    for (const int hint : {face(rng), exact.face, static_cast<int>(mesh.F.rows()) + 5}) {
      const auto hinted = tree.closest_point(p, std::numeric_limits<double>::infinity(), hint);
      ASSERT_TRUE(hinted);
      EXPECT_EQ(hinted->face, plain->face) << "hint " << hint;
      EXPECT_EQ(hinted->point, plain->point) << "hint " << hint;
    }
  }
}

TEST(AabbTree, NothingFartherThanTheLimitIsFoundEvenFromAHint) {
  const Mesh& mesh = test::procedural_mesh("creature");
  const AabbTree tree(mesh.V, mesh.F);
  const Eigen::Vector3d far(10, 10, 10);
  const double d = std::sqrt(brute_force(mesh, far).distance_squared);
  EXPECT_FALSE(tree.closest_point(far, 0.99 * d));
  EXPECT_FALSE(tree.closest_point(far, 0.99 * d, 0));
  EXPECT_TRUE(tree.closest_point(far, 1.01 * d, 0));
}

}  // namespace
}  // namespace meshmark
