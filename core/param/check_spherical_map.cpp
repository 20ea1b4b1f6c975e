#include "core/param/check_spherical_map.hpp"

#include <cmath>

#include "core/mesh/spherical_area.hpp"
#include "core/param/exact_orientation.hpp"

namespace meshmark {

bool SphericalMapCheck::bijective() const { return flipped_faces == 0 && std::abs(degree - 1.0) < 1e-6; }

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
