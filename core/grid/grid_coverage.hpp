#pragma once
// How well a mesh's vertices see each grid vertex's basis function: a carrier whose support holds
// almost no vertex moves none of them, and no reading of those vertices can tell its sign.

#include <vector>

#include "core/grid/sphere_grid.hpp"

namespace meshmark {

/// Per grid vertex k of levels [0, V_finest): Σ over the cells of w², w the weight of k in the
/// level-j triangle holding the cell's point, j the level at which k is born (`coarsest` for the
/// vertices of the coarsest level, which all live there): the energy a hat function of k's own
/// level leaves at the vertices. `cells` are located at grid level `level` ≥ `finest`.
Eigen::VectorXd grid_vertex_coverage(const SphereGrid& grid, int level, const std::vector<GridLocation>& cells,
                                     int coarsest, int finest);

}  // namespace meshmark
