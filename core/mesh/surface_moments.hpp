#pragma once
// The principal axes of a surface (area-weighted, exact over its triangles): how far its shape
// tells its turns apart. Registration searches the turns its axes cannot tell apart, and `info`
// warns about a shape about as wide every way (a ball), whose turned copies may not register.

#include <Eigen/Core>

#include "core/mesh/mesh.hpp"

namespace meshmark {

struct SurfaceMoments {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();   ///< columns, by decreasing variance
  Eigen::Vector3d variances = Eigen::Vector3d::Zero();  ///< along `axes`
};

/// The moments of the surface of `mesh` (zero-area faces weigh nothing).
SurfaceMoments surface_moments(const Mesh& mesh);

/// Two principal variances this close (the smaller at least this share of the larger) leave
/// their axes to noise.
inline constexpr double kAlikeVariances = 0.9;
inline bool variances_alike(double larger, double smaller) { return smaller > kAlikeVariances * larger; }

}  // namespace meshmark
