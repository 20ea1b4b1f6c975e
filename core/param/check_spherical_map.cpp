#include "core/param/check_spherical_map.hpp"

#include <cmath>

#include "core/param/exact_orientation.hpp"

namespace meshmark {

bool SphericalMapCheck::bijective() const { return flipped_faces == 0 && std::abs(degree - 1.0) < 1e-6; }

double signed_spherical_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  // Van Oosterom and Strackee: tan(Ω/2) = det(a,b,c) / (1 + a·b + b·c + c·a).
  return 2.0 * std::atan2(a.dot(b.cross(c)), 1.0 + a.dot(b) + b.dot(c) + c.dot(a));
}

SphericalMapCheck check_spherical_map(const Vertices& S, const Faces& F) {
  SphericalMapCheck check;
  double total = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = S.row(F(f, 0)), b = S.row(F(f, 1)), c = S.row(F(f, 2));
    if (orientation_sign(a, b, c) <= 0) {
      ++check.flipped_faces;
      check.flipped.push_back(static_cast<int>(f));
    }
    total += signed_spherical_area(a.normalized(), b.normalized(), c.normalized());
  }
  check.degree = total / (4.0 * M_PI);
  return check;
}

}  // namespace meshmark
