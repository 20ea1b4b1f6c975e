#pragma once
// Möbius centering (after Baden, Crane and Kazhdan 2018): the Möbius transformation of the
// sphere that moves the weighted centre of mass of points to the origin. It undoes the
// arbitrary "zoom" a conformal map is free to have, so no region is needlessly shrunk.

#include <Eigen/Core>

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct MobiusCenterOptions {
  int max_iterations = 100;
  double tolerance = 1e-10;  ///< stop when |Σ w_i x_i| / Σ w_i is below this
};

struct MobiusCenterResult {
  int iterations = 0;
  double residual = 0;  ///< |centre of mass| reached
};

/// Moves the unit vectors in the rows of `S` in place so that Σ w_i S_i ≈ 0.
MobiusCenterResult mobius_center(Vertices& S, const Eigen::VectorXd& weights, const MobiusCenterOptions& options = {});

/// The Möbius transformation x ↦ (1 − |c|²)(x + c)/|x + c|² + c, |c| < 1, which maps the unit
/// sphere to itself.
Eigen::Vector3d mobius_transform(const Eigen::Vector3d& x, const Eigen::Vector3d& c);

}  // namespace meshmark
