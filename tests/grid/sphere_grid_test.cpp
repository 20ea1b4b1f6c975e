#include "core/grid/sphere_grid.hpp"

#include <gtest/gtest.h>

#include <random>
#include <set>

#include "core/mesh/validate_mesh.hpp"
#include "core/mesh/spherical_area.hpp"
#include "core/param/check_spherical_map.hpp"

namespace meshmark {
namespace {

TEST(SphereGrid, VertexCountsFollowTheNestingFormula) {
  for (BaseSolid base : kBaseSolids) {
    const SphereGrid grid = make_sphere_grid(base, 4);
    for (int j = 0; j <= 4; ++j) EXPECT_EQ(grid.vertex_count(j), sphere_grid_vertex_count(base, j));
    EXPECT_EQ(grid.points.rows(), grid.vertex_count(4));
  }
}

TEST(SphereGrid, TetrahedronReachesLevelNine) {
  const SphereGrid grid = make_sphere_grid(BaseSolid::tetrahedron, 9);
  EXPECT_EQ(grid.points.rows(), 524290);
  EXPECT_EQ(grid.faces[9].rows(), 4 * (1 << 18));
}

TEST(SphereGrid, EveryLevelIsAClosedOutwardSphere) {
  for (BaseSolid base : kBaseSolids) {
    const SphereGrid grid = make_sphere_grid(base, 3);
    for (int j = 0; j <= 3; ++j) {
      Mesh level{grid.points.topRows(grid.vertex_count(j)), grid.faces[j]};
      const MeshReport r = validate_mesh(level);
      EXPECT_TRUE(r.closed_genus_zero) << to_string(base) << " level " << j;
      EXPECT_TRUE(check_spherical_map(level.V, level.F).bijective());
    }
  }
}

TEST(SphereGrid, ChildrenTileTheirParent) {
  const SphereGrid grid = make_sphere_grid(BaseSolid::octahedron, 2);
  for (int f = 0; f < grid.faces[1].rows(); ++f) {
    const auto& P = grid.points;
    double parent =
        signed_spherical_area(P.row(grid.faces[1](f, 0)), P.row(grid.faces[1](f, 1)), P.row(grid.faces[1](f, 2)));
    double children = 0;
    for (int c = 4 * f; c < 4 * f + 4; ++c)
      children +=
          signed_spherical_area(P.row(grid.faces[2](c, 0)), P.row(grid.faces[2](c, 1)), P.row(grid.faces[2](c, 2)));
    EXPECT_NEAR(children, parent, 1e-13);
  }
}

TEST(SphereGrid, StencilsAreTheButterflyNeighbourhood) {
  const SphereGrid grid = make_sphere_grid(BaseSolid::icosahedron, 3);
  for (int m = grid.vertex_count(0); m < grid.vertex_count(3); ++m) {
    const Stencil& s = grid.stencil(m);
    const int level = grid.level_of(m) - 1;
    // The new vertex is the normalized midpoint of its edge.
    EXPECT_LT((grid.points.row(m) - (grid.points.row(s.v1) + grid.points.row(s.v2)).normalized()).norm(), 1e-15);
    // All stencil vertices exist at the parent level and are distinct.
    std::set<int> distinct = {s.v1, s.v2, s.f1, s.f2, s.e[0], s.e[1], s.e[2], s.e[3]};
    EXPECT_EQ(distinct.size(), 8u);
    for (int v : distinct) EXPECT_LT(v, grid.vertex_count(level));
    // The butterfly is symmetric: f1 and f2 lie on opposite sides of the edge.
    const Eigen::Vector3d n = grid.points.row(s.v1).cross(grid.points.row(s.v2));
    EXPECT_GT(n.dot(grid.points.row(s.f1)), 0);
    EXPECT_LT(n.dot(grid.points.row(s.f2)), 0);
  }
}

TEST(SphereGrid, LocatedPointsAreReproducedByTheirWeights) {
  const SphereGrid grid = make_sphere_grid(BaseSolid::tetrahedron, 6);
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d p = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    const GridLocation l = locate_in_grid(grid, p, 6);
    const Faces& F = grid.faces[6];
    EXPECT_GE(l.bary.minCoeff(), 0.0);
    EXPECT_NEAR(l.bary.sum(), 1.0, 1e-12);
    const Eigen::Vector3d flat = l.bary[0] * grid.points.row(F(l.face, 0)) + l.bary[1] * grid.points.row(F(l.face, 1)) +
                                 l.bary[2] * grid.points.row(F(l.face, 2));
    EXPECT_LT((flat.normalized() - p).norm(), 1e-12);  // the gnomonic weights point back at p
  }
}

// Sampling goes on from each vertex's face of the level before (sample_on_grid): the face must be
// the whole descent's, on grid vertices and edges too, where the margins tie.
TEST(SphereGrid, ADescentGoneOnFromACoarserLevelEndsInTheWholeDescentsFace) {
  for (BaseSolid base : kBaseSolids) {
    const SphereGrid grid = make_sphere_grid(base, 5);
    std::mt19937 rng(11);
    std::normal_distribution<double> normal;
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 500; ++i) points.push_back(Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized());
    for (int v = 0; v < grid.vertex_count(5); v += 7) points.push_back(grid.points.row(v).transpose());
    for (const Eigen::Vector3d& p : points) {
      int face = descend_grid(grid, p, -1, 0, 1);
      for (int level = 2; level <= 5; ++level) {
        face = descend_grid(grid, p, level - 1, face, level);
        const GridLocation whole = locate_in_grid(grid, p, level), stepped = grid_location(grid, p, level, face);
        ASSERT_EQ(stepped.face, whole.face) << "level " << level;
        ASSERT_EQ(stepped.bary, whole.bary);
      }
    }
  }
}

TEST(SphereGrid, LocatingAGridVertexGivesWeightOneOnIt) {
  const SphereGrid grid = make_sphere_grid(BaseSolid::icosahedron, 4);
  for (int v : {0, 17, 200, grid.vertex_count(4) - 1}) {
    const GridLocation l = locate_in_grid(grid, grid.points.row(v), 4);
    const Faces& F = grid.faces[4];
    int k;
    l.bary.maxCoeff(&k);
    EXPECT_EQ(F(l.face, k), v);
    EXPECT_NEAR(l.bary[k], 1.0, 1e-12);
  }
}

TEST(SphereGrid, RefusesLevelsOutOfRange) {
  EXPECT_THROW(make_sphere_grid(BaseSolid::tetrahedron, -1), std::invalid_argument);
  EXPECT_THROW(make_sphere_grid(BaseSolid::tetrahedron, 13), std::invalid_argument);
}

}  // namespace
}  // namespace meshmark
