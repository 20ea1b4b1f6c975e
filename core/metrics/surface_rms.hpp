#pragma once
// The RMS over a surface of a scalar field given at its vertices and linear on each triangle:
// sqrt(∫ u² dA / ∫ dA), integrated exactly (the consistent mass matrix, not the lumped one).
// A displacement that alternates between neighbouring vertices has a smaller surface RMS than
// its vertex values suggest; the surface RMS is what a surface-distance metric (MRMS) sees.

#include <Eigen/Core>

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// `u`: one value per vertex of `mesh` (#V). Zero-area faces do not count; 0 for no area.
double surface_rms(const Mesh& mesh, const Eigen::VectorXd& u);

}  // namespace meshmark
