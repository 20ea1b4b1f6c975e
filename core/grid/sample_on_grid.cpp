#include "core/grid/sample_on_grid.hpp"

#include <algorithm>
#include <stdexcept>

#include "core/util/parallel_for.hpp"

namespace meshmark {

Eigen::MatrixXd interpolate_from_grid(const SphereGrid& grid, int level, const std::vector<GridLocation>& cells,
                                      const Eigen::MatrixXd& values, int threads) {
  const Faces& F = grid.faces[static_cast<std::size_t>(level)];
  Eigen::MatrixXd out(static_cast<Eigen::Index>(cells.size()), values.cols());
  parallel_for(static_cast<std::int64_t>(cells.size()), threads, [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t i = begin; i < end; ++i) {
      const GridLocation& c = cells[i];
      out.row(i) = c.bary[0] * values.row(F(c.face, 0)) + c.bary[1] * values.row(F(c.face, 1)) +
                   c.bary[2] * values.row(F(c.face, 2));
    }
  });
  return out;
}

GridSampling sample_on_grid(const Vertices& V, const Faces& F, const Vertices& S, const SphereGrid& grid,
                            const SamplingOptions& options, int threads) {
  if (options.max_level > grid.levels || options.start_level > options.max_level || options.start_level < 0)
    throw std::invalid_argument("sampling levels " + std::to_string(options.start_level) + ".." +
                                std::to_string(options.max_level) + " do not fit a grid of " +
                                std::to_string(grid.levels) + " levels");
  const double diagonal = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  const SphericalMeshLocator locator(S, F);
  const Eigen::MatrixXd vertices = V;
  GridSampling result;

  for (int level = options.start_level; level <= options.max_level; ++level) {
    // Levels are nested: only the vertices new at this level need locating.
    const int have = static_cast<int>(result.samples.size()), need = grid.vertex_count(level);
    const std::vector<SurfaceLocation> added = locate_all(locator, grid.points.middleRows(have, need - have), threads);
    result.samples.insert(result.samples.end(), added.begin(), added.end());
    result.level = level;

    // Inverse sampling: every original vertex rebuilt from the grid samples around it.
    result.positions = interpolate_at(F, result.samples, vertices, threads);
    // Each vertex's descent goes on from the level before: the faces locate_in_grid gives.
    const int located = result.vertex_cells.empty() ? -1 : level - 1;
    result.vertex_cells.resize(static_cast<std::size_t>(V.rows()));
    parallel_for(V.rows(), threads, [&](std::int64_t begin, std::int64_t end) {
      for (std::int64_t i = begin; i < end; ++i) {
        GridLocation& cell = result.vertex_cells[static_cast<std::size_t>(i)];
        const Eigen::Vector3d p = S.row(i).transpose();
        cell = grid_location(grid, p, level, descend_grid(grid, p, located, cell.face, level));
      }
    });
    const Eigen::MatrixXd rebuilt = interpolate_from_grid(grid, level, result.vertex_cells, result.positions, threads);
    result.error = (rebuilt - vertices).rowwise().norm().maxCoeff() / diagonal;
    result.error_by_level.push_back(result.error);
    result.reached_epsilon = result.error < options.epsilon;
    if (result.reached_epsilon) break;
  }
  return result;
}

}  // namespace meshmark
