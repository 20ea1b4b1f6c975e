#pragma once
// Trimmed point-to-plane ICP with uniform scale, the step every registration start is refined
// by: only the best-matching fraction of the correspondences counts, so noise, crops and pieces do
// not pull the fit. Internal to core/registration (align_meshes.hpp is the interface).

#include <functional>

#include "core/mesh/similarity.hpp"
#include "core/registration/align_meshes.hpp"
#include "core/util/job_control.hpp"

namespace meshmark::registration {

// A correspondence: a point on (or near) the original and the normal of the plane there; `id`
// names it (a sample, a face) for the next step's search.
struct Match {
  Eigen::Vector3d point, normal;
  double distance_squared;
  int id = -1;
};
// The match of a point, given the id of the last step's match for it (-1: none): a step moves the
// points little, so it bounds the search from the start. The match is the same with or without.
using Matcher = std::function<Match(const Eigen::Vector3d&, int hint)>;

/// The nearest of the original's dense samples (fast; a floor of about 1e-5 of the diagonal).
Matcher nearest_sample(const RegistrationTarget& target);
/// The exact closest point on the original's triangles.
Matcher closest_surface_point(const RegistrationTarget& target);

/// Up to `iterations` trimmed steps of `P` (suspect coordinates) moved by T toward `match`;
/// stops when a step moves less than `tolerance` × the diagonal or the scale runs past
/// kMaxScaleChange from its start. `hold_scale`: T's scale is kept. Returns the RMS of the kept
/// plane distances; `used` is the steps taken.
double run_icp(const Vertices& P, const Matcher& match, double diagonal, int iterations, double trim, double tolerance,
               Similarity& T, int& used, const JobControl* control, bool hold_scale = false);

/// Trimmed sum of squared distances from T(P) to the target's samples, without iterating.
double score(const Vertices& P, const RegistrationTarget& target, double trim, const Similarity& T,
             const JobControl* control);

}  // namespace meshmark::registration
