#pragma once
// Regular resampling of a mesh on the spherical grid (the paper's step 2), with its level rule:
// start at level 5 and refine until resampling back reproduces every original vertex within ε,
// up to a cap, reporting the error reached.

#include <vector>

#include "core/grid/sphere_grid.hpp"
#include "core/grid/spherical_mesh_locator.hpp"
#include "core/mesh/mesh.hpp"

namespace meshmark {

struct SamplingOptions {
  int start_level = 5;
  int max_level = 9;       ///< the cap (tetrahedron level 9: 524,290 samples)
  double epsilon = 0.005;  ///< ε, as a fraction of the bounding-box diagonal
};

struct GridSampling {
  int level = 0;                           ///< the finest grid level used, J
  double error = 0;                        ///< max_i |v'_i − v_i| at level J, as a fraction of the bbox diagonal
  bool reached_epsilon = false;            ///< error < ε (false when the cap stopped the refinement)
  std::vector<double> error_by_level;      ///< the error at start_level, start_level+1, ..., J
  std::vector<SurfaceLocation> samples;    ///< V_J: where each grid vertex lies on the mesh
  Eigen::MatrixXd positions;               ///< V_J×3: the mesh sampled at the grid vertices
  std::vector<GridLocation> vertex_cells;  ///< #V: where each mesh vertex lies in the grid at level J
};

/// Samples mesh V (faces F, spherical image S) on `grid`, choosing the level by the rule above.
/// The grid must be built to at least options.max_level. Runs on `threads` threads (0: the
/// hardware's); the result does not depend on the count.
GridSampling sample_on_grid(const Vertices& V, const Faces& F, const Vertices& S, const SphereGrid& grid,
                            const SamplingOptions& options = {}, int threads = 0);

/// Values on the grid vertices of level `level` interpolated at each mesh vertex's cell:
/// #cells × values.cols(). The inverse sampling of the paper. On `threads` threads (0: the hardware's).
Eigen::MatrixXd interpolate_from_grid(const SphereGrid& grid, int level, const std::vector<GridLocation>& cells,
                                      const Eigen::MatrixXd& values, int threads = 0);

}  // namespace meshmark
