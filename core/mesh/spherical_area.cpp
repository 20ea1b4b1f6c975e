#include "core/mesh/spherical_area.hpp"

#include <cmath>

#include <Eigen/Geometry>

namespace meshmark {

double signed_spherical_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  // Van Oosterom and Strackee: tan(Ω/2) = det(a,b,c) / (1 + a·b + b·c + c·a).
  return 2.0 * std::atan2(a.dot(b.cross(c)), 1.0 + a.dot(b) + b.dot(c) + c.dot(a));
}

}  // namespace meshmark
