#pragma once
// The area-correcting step. Conformal maps shrink protrusions (ears, limbs, fingers) to specks
// of the sphere, which a regular grid then cannot sample. This step moves the points of a
// bijective spherical map so that each region's share of the sphere approaches its share of the
// surface: the density ρ (surface share / sphere share) lives on a fixed coarse spherical grid,
// evolves by the heat equation, and carries the points along v = −∇ρ/ρ (a diffusion cartogram,
// after Gastner and Newman 2004). Mass moves with the points, so as ρ flattens every region
// approaches its fair share.
//
// Bijectivity holds by construction: after every step each triangle's orientation is checked
// exactly; the corners of a triangle that would fold stay put for that step, and a step that
// still folds one is retried at half the size.

#include <vector>

#include "core/grid/sphere_grid.hpp"
#include "core/mesh/mesh.hpp"
#include "core/util/job_control.hpp"

namespace meshmark {

struct EqualizeAreaOptions {
  /// Density grid levels (icosahedron), coarse to fine, one pass each. Empty: the finest level
  /// with at least `vertices_per_grid_point` mesh points per grid point (within [2, 5]), then
  /// one level finer: the coarse pass moves whole limbs, the fine one their tips.
  std::vector<int> grid_levels;
  double vertices_per_grid_point = 8;
  int max_steps = 200;
  double tolerance = 0.05;  ///< stop when max |ρ − 1| on the grid is below this
  double max_strain = 0.2;  ///< per step, time step × largest velocity gradient
  double max_time = 2.0;    ///< diffusion time at most (the sphere relaxes as e^{−2t})
  int freeze_rounds = 8;    ///< per step, rounds of freezing the corners of would-be folds
};

struct EqualizeAreaResult {
  std::vector<int> grid_levels;
  int steps = 0;
  int rejected_steps = 0;    ///< step attempts undone because a triangle would have folded
  double spread_before = 0;  ///< max |ρ − 1| on the density grids before
  double spread_after = 0;   ///< max |ρ − 1| on the finest density grid after
  double time = 0;           ///< diffusion time reached
};

/// Moves the unit vectors S (one per mesh vertex, a bijective map with faces F) in place.
/// `face_mass` is each face's share of the surface (any positive scale). Deterministic.
EqualizeAreaResult equalize_area(Vertices& S, const Faces& F, const Eigen::VectorXd& face_mass,
                                 const EqualizeAreaOptions& options = {}, const JobControl* control = nullptr);

}  // namespace meshmark
