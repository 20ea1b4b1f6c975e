#pragma once
// The exact sign of det(a, b, c) = a · (b × c): whether the triangle (a, b, c) winds
// counter-clockwise seen from outside the origin. Used to prove a spherical map bijective, so it
// must never be wrong: a fast floating-point answer when it is provably right, exact expansion
// arithmetic (error-free products and sums) otherwise.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace meshmark {

/// +1, 0 or −1: the sign of det(a, b, c), exactly.
int orientation_sign(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace meshmark
