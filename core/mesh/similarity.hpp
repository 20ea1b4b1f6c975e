#pragma once
// A similarity of 3-space: rotation, uniform scale and translation. Registration finds one, the
// similarity attack applies one.

#include <Eigen/Core>

#include "core/mesh/mesh.hpp"

namespace meshmark {

/// x ↦ scale · R x + t
struct Similarity {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  double scale = 1;
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  Eigen::Vector3d apply(const Eigen::Vector3d& x) const { return scale * (R * x) + t; }
  /// Each row of V (#V×3) mapped.
  Vertices apply_to_rows(const Vertices& V) const;
  Similarity inverse() const;
};

/// The least-squares similarity taking the columns of `from` onto those of `to` (Umeyama).
Similarity fit_similarity(const Eigen::Matrix3Xd& from, const Eigen::Matrix3Xd& to);

}  // namespace meshmark
