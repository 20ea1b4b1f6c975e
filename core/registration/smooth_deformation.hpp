#pragma once
// Non-rigid alignment: after the rigid fit, a copy that was bent, twisted, posed or warped is
// unbent by a displacement field far smoother than the mark's coarsest band — a polynomial of low
// total degree in the original's coordinates (20 terms per axis at degree 3) — fitted as
// point-to-plane ICP fits a pose. Its few degrees of freedom cannot follow the mark's thousands of
// keyed carriers, so removing it leaves the mark; it is kept only where it fits the copy much
// better than the rigid pose alone.

#include <Eigen/Core>

#include "core/mesh/mesh.hpp"
#include "core/spatial/aabb_tree.hpp"
#include "core/util/job_control.hpp"

namespace meshmark {

struct DeformationOptions {
  int degree = 3;                ///< total degree of the polynomial field
  int iterations = 15;           ///< ICP steps (closest points, then the field's least squares)
  double trim = 0.9;             ///< share of the correspondences the fit's RMS counts (the closest)
  double fit_trim = 0.97;        ///< share the field is fitted to (the closest; the rest: outliers)
  double regularization = 1e-5;  ///< Tikhonov weight on the coefficients, per correspondence
  /// Kept only when what the fit leaves above a mark's own residual (min_rigid_rms) falls below
  /// this share of what the rigid pose left above it.
  double min_gain = 0.5;
  /// A rigid pose closer than this share of the diagonal is not tried: a mark at the default
  /// strength alone leaves about 0.036 % (the bunny), and a field cannot take the mark away.
  double min_rigid_rms = 0.0004;
};

/// x ↦ x + Σₖ cₖ mₖ((x − centre) / unit), mₖ the monomials of total degree ≤ degree.
struct SmoothDeformation {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double unit = 1;
  int degree = 0;
  Eigen::MatrixX3d coefficients;  ///< one row per monomial; empty: the identity
  Eigen::Vector3d apply(const Eigen::Vector3d& x) const;
  Vertices apply_to_rows(const Vertices& V) const;
  bool identity() const { return coefficients.rows() == 0; }
};

/// What a fit found: the field and the trimmed RMS distances (in the original's units) before
/// and after it.
struct DeformationFit {
  SmoothDeformation deformation;
  double rigid_rms = 0, deformed_rms = 0;
};

/// Whether `fit` (of a shape of bounding-box diagonal `diagonal`) is worth keeping
/// (DeformationOptions::min_gain): a twisted body of revolution leaves the rigid pose little above
/// the mark's own residual, and a field that takes most of that away is what unbends it.
bool fits_much_better(const DeformationFit& fit, double diagonal, const DeformationOptions& options);

/// Fits the field taking `points` (a copy's surface samples, already rigidly aligned) onto the
/// surface in `tree` (whose faces have `face_normals`), of bounding-box diagonal `diagonal`.
/// Polls `control`.
DeformationFit fit_smooth_deformation(const Vertices& points, const AabbTree& tree, const Vertices& face_normals,
                                      double diagonal, const DeformationOptions& options = {},
                                      const JobControl* control = nullptr);

}  // namespace meshmark
