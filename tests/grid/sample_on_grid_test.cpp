#include "core/grid/sample_on_grid.hpp"

#include <gtest/gtest.h>

#include "core/param/sphere_param.hpp"
#include "tests/test_data.hpp"

namespace meshmark {
namespace {

TEST(SphericalMeshLocator, FindsTheTriangleUnderEveryGridPoint) {
  const Mesh sphere = test::icosphere(3);
  const SphericalMeshLocator locator(sphere.V, sphere.F);
  const SphereGrid grid = make_sphere_grid(BaseSolid::octahedron, 5);
  for (Eigen::Index i = 0; i < grid.points.rows(); ++i) {
    const Eigen::Vector3d p = grid.points.row(i);
    const SurfaceLocation l = locator.locate(p);
    EXPECT_GE(l.bary.minCoeff(), 0.0);
    const Eigen::Vector3d flat = l.bary[0] * sphere.V.row(sphere.F(l.face, 0)) +
                                 l.bary[1] * sphere.V.row(sphere.F(l.face, 1)) +
                                 l.bary[2] * sphere.V.row(sphere.F(l.face, 2));
    EXPECT_LT((flat.normalized() - p).norm(), 1e-12);
  }
}

TEST(SampleOnGrid, ASphereSampledOnItsOwnGridIsReproducedExactly) {
  // A mesh that is a grid level itself, mapped by the identity: its vertices are grid vertices.
  const SphereGrid grid = make_sphere_grid(BaseSolid::icosahedron, 6);
  const Vertices V = grid.points.topRows(grid.vertex_count(3));
  const Faces& F = grid.faces[3];
  SamplingOptions options;
  options.start_level = 3;
  options.max_level = 6;
  options.epsilon = 1e-9;
  const GridSampling s = sample_on_grid(V, F, V, grid, options);
  EXPECT_EQ(s.level, 3);
  EXPECT_TRUE(s.reached_epsilon);
  EXPECT_LT(s.error, 1e-12);
}

TEST(SampleOnGrid, ErrorShrinksAsTheLevelRisesAndTheCapIsReported) {
  const Mesh& creature = test::procedural_mesh("creature");
  const SphereParam p = sphere_param(creature);
  const SphereGrid grid = make_sphere_grid(BaseSolid::tetrahedron, 8);
  SamplingOptions options;
  options.max_level = 8;
  options.epsilon = 1e-6;  // out of reach: the rule must stop at the cap and say so
  const GridSampling s = sample_on_grid(creature.V, p.F, p.S, grid, options);
  EXPECT_EQ(s.level, 8);
  EXPECT_FALSE(s.reached_epsilon);
  ASSERT_EQ(s.error_by_level.size(), 4u);
  EXPECT_LT(s.error_by_level.back(), s.error_by_level.front() / 2);
  EXPECT_EQ(s.positions.rows(), grid.vertex_count(8));
}

TEST(SampleOnGrid, StopsAtTheFirstLevelWithinEpsilon) {
  const Mesh& creature = test::procedural_mesh("creature");
  const SphereParam p = sphere_param(creature);
  const SphereGrid grid = make_sphere_grid(BaseSolid::tetrahedron, 9);
  SamplingOptions options;
  options.epsilon = 0.05;
  const GridSampling s = sample_on_grid(creature.V, p.F, p.S, grid, options);
  EXPECT_TRUE(s.reached_epsilon);
  EXPECT_LT(s.error, 0.05);
  for (std::size_t i = 0; i + 1 < s.error_by_level.size(); ++i) EXPECT_GE(s.error_by_level[i], 0.05);
}

TEST(SampleOnGrid, SamplesLieOnTheMesh) {
  const Mesh& creature = test::procedural_mesh("creature");
  const SphereParam p = sphere_param(creature);
  const SphereGrid grid = make_sphere_grid(BaseSolid::octahedron, 6);
  SamplingOptions options;
  options.start_level = options.max_level = 6;
  const GridSampling s = sample_on_grid(creature.V, p.F, p.S, grid, options);
  const AabbTree tree(creature.V, creature.F);
  const double diagonal = (creature.V.colwise().maxCoeff() - creature.V.colwise().minCoeff()).norm();
  for (Eigen::Index i = 0; i < s.positions.rows(); i += 7)
    EXPECT_LT(std::sqrt(tree.closest_point(s.positions.row(i).transpose())->distance_squared), 1e-12 * diagonal);
}

}  // namespace
}  // namespace meshmark
