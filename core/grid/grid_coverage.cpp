#include "core/grid/grid_coverage.hpp"

#include <stdexcept>

namespace meshmark {

namespace {

// The point of the sphere a cell stands for: its weights of the flat triangle, pushed out.
Eigen::Vector3d cell_point(const SphereGrid& grid, int level, const GridLocation& cell) {
  const Faces& F = grid.faces[static_cast<std::size_t>(level)];
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) p += cell.bary[k] * grid.points.row(F(cell.face, k)).transpose();
  return p.normalized();
}

}  // namespace

Eigen::VectorXd grid_vertex_coverage(const SphereGrid& grid, int level, const std::vector<GridLocation>& cells,
                                     int coarsest, int finest) {
  if (!(0 <= coarsest && coarsest <= finest && finest <= level && level <= grid.levels))
    throw std::invalid_argument("grid coverage: levels out of order");
  Eigen::VectorXd energy = Eigen::VectorXd::Zero(grid.vertex_count(finest));
  for (const GridLocation& cell : cells) {
    const Eigen::Vector3d p = cell_point(grid, level, cell);
    for (int j = coarsest; j <= finest; ++j) {
      const int face = cell.face >> (2 * (level - j));  // faces 4f..4f+3 are f's children
      const Faces& F = grid.faces[static_cast<std::size_t>(j)];
      const Eigen::Vector3d w = gnomonic_barycentric(p, grid.points.row(F(face, 0)), grid.points.row(F(face, 1)),
                                                     grid.points.row(F(face, 2)));
      const int born_before = j == coarsest ? 0 : grid.vertex_count(j - 1);
      for (int k = 0; k < 3; ++k)
        if (F(face, k) >= born_before) energy[F(face, k)] += w[k] * w[k];
    }
  }
  return energy;
}

}  // namespace meshmark
