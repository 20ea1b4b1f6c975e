// The closest-point query against brute force over every triangle, with and without a hint.

#include "core/spatial/aabb_tree.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/attacks/subdivide.hpp"
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

// Every leaf but one is full whatever the face count, on one thread or several: a tree holds
// about half a node per face (splitting counts in exact halves left two-face leaves on some
// counts, a node per face). Answers stay brute force's (the tests above and below).
TEST(AabbTree, EveryLeafButOneIsFull) {
  const Mesh big = subdivide(test::procedural_mesh("creature_large"), SubdivisionScheme::loop, 2);
  for (const Eigen::Index faces : {Eigen::Index{5}, Eigen::Index{17}, Eigen::Index{1000}, Eigen::Index{4 * 1024 + 1},
                                   big.F.rows() / 2 + 3, big.F.rows()})
    for (const int threads : {1, 4}) {
      const Faces F = big.F.topRows(faces);
      const AabbTree tree(big.V, F, threads);
      const auto leaves = static_cast<std::size_t>((faces + 3) / 4);
      EXPECT_EQ(tree.node_count(), 2 * leaves - 1) << faces << " faces, " << threads << " threads";
    }
}

// Above 65,536 triangles a tree's halves are built on separate threads: every answer is the one
// a tree built on one thread gives, and the closest points are still the true ones.
TEST(AabbTree, ATreeBuiltOnManyThreadsAnswersAsOneBuiltOnOne) {
  const Mesh mesh = subdivide(test::procedural_mesh("creature_large"), SubdivisionScheme::loop, 2);
  ASSERT_GT(mesh.F.rows(), 4 << 16);
  const AabbTree one(mesh.V, mesh.F, 1), four(mesh.V, mesh.F, 4);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    const auto a = one.closest_point(p), b = four.closest_point(p);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->face, b->face);
    EXPECT_EQ(a->point, b->point);
    if (i % 100 == 0) {
      EXPECT_EQ(b->distance_squared, brute_force(mesh, p).distance_squared);
    }
    const auto hit_a = one.first_hit(Eigen::Vector3d::Zero(), p, 0, 10),
               hit_b = four.first_hit(Eigen::Vector3d::Zero(), p, 0, 10);
    ASSERT_EQ(hit_a.has_value(), hit_b.has_value());
    if (hit_a) {
      EXPECT_EQ(hit_a->face, hit_b->face);
      EXPECT_EQ(hit_a->t, hit_b->t);
    }
  }
}

}  // namespace
}  // namespace meshmark
