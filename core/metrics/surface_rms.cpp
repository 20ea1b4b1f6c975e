#include "core/metrics/surface_rms.hpp"

#include <cmath>
#include <stdexcept>

namespace meshmark {

double surface_rms(const Mesh& mesh, const Eigen::VectorXd& u) {
  if (u.size() != mesh.V.rows()) throw std::invalid_argument("surface_rms: one value per vertex is needed");
  double integral = 0, area = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    const Eigen::Vector3d pa = mesh.V.row(a), pb = mesh.V.row(b), pc = mesh.V.row(c);
    const double face_area = 0.5 * (pb - pa).cross(pc - pa).norm();
    // ∫ over the triangle of the linear interpolant squared: A/6 (Σ uᵢ² + Σ_{i<j} uᵢ uⱼ).
    const double ua = u[a], ub = u[b], uc = u[c];
    integral += face_area / 6 * (ua * ua + ub * ub + uc * uc + ua * ub + ub * uc + uc * ua);
    area += face_area;
  }
  return area > 0 ? std::sqrt(integral / area) : 0.0;
}

}  // namespace meshmark
