#pragma once
// Conformalized mean curvature flow (Kazhdan, Solomon and Ben-Chen 2012): a genus-0 surface
// flows towards a round sphere while staying conformal to the original. The stiffness matrix is
// the original's (fixed) cotangent Laplacian; each step rebuilds the mass matrix from the current
// positions and solves (M + t L) X = M X_prev, then re-centres and re-scales to unit area.
//
// Only the first system is factorized (supernodal Cholesky, CHOLMOD). Later steps solve by
// conjugate gradients preconditioned with that factor, warm-started from the previous positions:
// L is fixed and M changes slowly, so a handful of iterations reach the loose tolerance a flow
// step needs. A step whose CG stalls refactorizes.

#include "core/mesh/mesh.hpp"
#include "core/param/cotmatrix.hpp"
#include "core/util/job_control.hpp"

namespace meshmark {

struct ConformalFlowOptions {
  double time_step = 0.2;  ///< t, for a surface of unit area
  int min_iterations = 3;
  int max_iterations = 40;
  /// Stop when the mass-weighted RMS of |x| − r̄, relative to r̄, is below this: round enough
  /// that projecting to the sphere moves little.
  double roundness_tolerance = 0.05;
  double solve_tolerance = 1e-3;  ///< relative residual of each step's solve
  int max_cg_iterations = 12;     ///< refactorize when CG needs more
  CotmatrixOptions stiffness;
};

struct ConformalFlowResult {
  Vertices X;  ///< the flowed surface: unit area, area-weighted centroid at the origin
  int iterations = 0;
  int factorizations = 0;
  double roundness = 0;  ///< the last relative RMS radial deviation
};

/// Flows a unit-area, centred, outward mesh. Throws std::runtime_error if the linear system
/// cannot be factorized.
/// Polls `control` at every step.
ConformalFlowResult conformal_flow(const Vertices& V, const Faces& F, const ConformalFlowOptions& options = {},
                                   const JobControl* control = nullptr);

/// Relative mass-weighted RMS deviation of the distances to the origin from their mean.
double roundness(const Vertices& X, const Eigen::VectorXd& mass);

}  // namespace meshmark
