#pragma once
// Registration by local shape, for a copy that kept no vertex of the original (remeshed,
// simplified, noisy) and lost part of its surface, so that its principal axes no longer point
// the original's way. Points spread evenly over each surface carry a histogram of how the surface
// turns around them: the angles between a point's normal, its neighbours' normals and the
// directions to them, as in FPFH (Rusu et al. 2009), read without the normals' signs so that a
// copy wound inconsistently describes itself alike. Each suspect point is matched to the
// original point of the nearest histogram, both ways; the similarities the matches vote for
// (pose_vote.hpp) are starts for the fit (align_meshes.hpp).

#include <Eigen/Core>
#include <vector>

#include "core/mesh/mesh.hpp"
#include "core/mesh/similarity.hpp"
#include "core/registration/pose_vote.hpp"
#include "core/util/job_control.hpp"

namespace meshmark {

/// Bins of each of the descriptor's three angle histograms.
inline constexpr int kFeatureBins = 11;

struct FeatureOptions {
  int original_points = 4000;  ///< points on the original that carry a descriptor
  int neighbours = 40;         ///< each descriptor's neighbourhood: the nearest points
  /// The suspect gets points as densely per area as the original, by its guessed scale, within:
  int min_suspect_points = 300;
  int max_suspect_points = 12000;
  /// A match agrees with a pose when it lands within this many of the original's point spacings.
  double tolerance_spacings = 2.5;
  PoseVoteOptions vote;
};

/// The descriptor of each of `points` (unit `normals`, zero where unknown) among its `neighbours`
/// nearest: #points × 3·kFeatureBins, each histogram summing to 1. The same for the points moved,
/// turned or scaled, and for any of the normals flipped.
Eigen::MatrixXd describe_points(const Vertices& points, const Vertices& normals, int neighbours, int threads);

/// Points on a surface with their descriptors (#points × 3·kFeatureBins).
struct ShapeFeatures {
  ShapeFeatures(const Mesh& mesh, Eigen::Index count, int neighbours, int threads);
  ShapeFeatures(const ShapeFeatures&) = delete;
  ShapeFeatures& operator=(const ShapeFeatures&) = delete;
  Vertices points;
  Eigen::MatrixXd descriptors;
  double area = 0;  ///< of the surface
};

/// The similarities (suspect → original) the suspect's local shape votes for, best supported
/// first; none when too few matches agree. `scale_guess` (original size / suspect size) sets the
/// suspect's point density. Deterministic. Polls `control`.
std::vector<Similarity> match_features(const Mesh& suspect, double scale_guess, const ShapeFeatures& original,
                                       const FeatureOptions& options = {}, const JobControl* control = nullptr);

}  // namespace meshmark
