#pragma once
// RANSAC over point matches between a suspect and the original: three matches whose triangles
// have the same shape imply a similarity; the one most matches agree with wins, then the next
// among those left, so that a part the original repeats gives each of its poses. Used by the
// matches of kept vertices (match_vertices.hpp) and of local shape (match_features.hpp).

#include <Eigen/Core>
#include <vector>

#include "core/mesh/similarity.hpp"
#include "core/util/job_control.hpp"

namespace meshmark {

struct PointMatch {
  Eigen::Vector3d suspect, original;
  int original_index;  ///< which original point: a pose that piles many matches onto one proves nothing
};

struct PoseVoteOptions {
  int max_trials = 20000;  ///< RANSAC draws of three matches
  /// A pose is accepted when at least this many matches, and this share of them, agree.
  int min_agreeing = 12;
  double min_agreeing_share = 0.05;
  int max_poses = 6;  ///< distinct poses returned at most
};

/// The similarities (suspect → original) that matches vote for, best supported first: a match
/// agrees with a pose that lands its suspect point within `tolerance` of its original point.
/// Poses after the first need a third of its support. `original_count` bounds original_index.
/// Deterministic (fixed seed). Polls `control`.
std::vector<Similarity> vote_poses(const std::vector<PointMatch>& matches, std::size_t original_count, double tolerance,
                                   const PoseVoteOptions& options = {}, const JobControl* control = nullptr);

}  // namespace meshmark
