#pragma once
// The area of a triangle on the unit sphere: the grid's cell areas (wavelet/), the map's degree
// (param/) and the equal-area checks all measure with it.

#include <Eigen/Core>

namespace meshmark {

/// Signed area of the spherical triangle (a, b, c) on the unit sphere, in steradians; positive
/// when (a, b, c) turns counter-clockwise seen from outside. a, b, c: unit vectors.
double signed_spherical_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace meshmark
