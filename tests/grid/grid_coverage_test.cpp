// A grid vertex's coverage is what the mesh's vertices see of a hat function of its own level:
// a vertex standing on it sees all of it, a hemisphere with no vertex sees none.

#include "core/grid/grid_coverage.hpp"

#include <gtest/gtest.h>

namespace meshmark {
namespace {

constexpr int kLevel = 4;

const SphereGrid& grid() {
  static const SphereGrid g = make_sphere_grid(BaseSolid::octahedron, kLevel);
  return g;
}

// Cells at the grid points (of the finest level) above z = 0.05, or at all of them.
std::vector<GridLocation> cells_at_points(bool upper_only) {
  std::vector<GridLocation> cells;
  for (Eigen::Index i = 0; i < grid().points.rows(); ++i)
    if (!upper_only || grid().points(i, 2) > 0.05)
      cells.push_back(locate_in_grid(grid(), grid().points.row(i).transpose(), kLevel));
  return cells;
}

TEST(GridCoverage, AVertexStandingOnAGridVertexSeesAllOfItsHat) {
  const Eigen::VectorXd coverage = grid_vertex_coverage(grid(), kLevel, cells_at_points(false), 1, 3);
  ASSERT_EQ(coverage.size(), grid().vertex_count(3));
  EXPECT_GE(coverage.minCoeff(), 1.0 - 1e-9);
  // A vertex born at level 3 (valence 6) sees itself whole and its six edges' midpoints, the
  // points of level 4 nearest it, at half height: 1 + 6 · 0.25. Nothing of a coarser or finer hat.
  for (int k = grid().vertex_count(2); k < grid().vertex_count(3); ++k)
    EXPECT_NEAR(coverage[k], 2.5, 1e-9) << "grid vertex " << k;
}

TEST(GridCoverage, AHemisphereWithoutVerticesIsNotCovered) {
  const Eigen::VectorXd coverage = grid_vertex_coverage(grid(), kLevel, cells_at_points(true), 1, 3);
  for (Eigen::Index k = 0; k < coverage.size(); ++k) {
    const double z = grid().points(k, 2);
    if (z < -0.5) {
      EXPECT_EQ(coverage[k], 0.0) << "grid vertex " << k;
    } else if (z > 0.1) {
      EXPECT_GE(coverage[k], 1.0 - 1e-9) << "grid vertex " << k;
    }
  }
}

TEST(GridCoverage, LevelsOutOfOrderAreRefused) {
  EXPECT_THROW(grid_vertex_coverage(grid(), kLevel, {}, 3, 2), std::invalid_argument);
  EXPECT_THROW(grid_vertex_coverage(grid(), kLevel, {}, 1, kLevel + 1), std::invalid_argument);
}

}  // namespace
}  // namespace meshmark
